"""The analyses of the bearing at a speed: the static equilibrium, the force coefficients about
it, and the linear stability of a rigid rotor on them.

Each takes the case (or the result of the one before) and returns a result object; the film
they share is :mod:`foilbearing.reynolds` and :mod:`foilbearing.film`. The old module names
(``foilbearing.static``, ``foilbearing.coefficients``, ``foilbearing.stability``) are the same
modules under the names they had before this package.

=================  =============================================================================
module             responsibility
=================  =============================================================================
``equilibrium``    static analysis: the journal equilibrium under load (Newton on film and
                   position), or the film at a given position
``static_result``  the result of a static analysis and its views (headline, summary, Dataset,
                   plot)
``coefficients``   dynamic force coefficients: stiffness and damping against excitation
                   frequency
``stability``      linear stability of a rigid rotor on the bearing: whirl eigenvalues and onset
                   speed
=================  =============================================================================
"""
