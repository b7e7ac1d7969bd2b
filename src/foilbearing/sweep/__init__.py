"""Parameter sweeps, from a laptop to a Dask cluster.

============  ==================================================================================
module        responsibility
============  ==================================================================================
``spec``      the sweep file: parameters, their units and values, the validated grid
``analyses``  what each grid point computes (static, coefficients, stability)
``runner``    ``run_sweep``: one Dask task per point, each written as it finishes
``cluster``   the Dask client: an existing scheduler's, or a new local cluster's
``records``   the results folder of a sweep or sample: manifest and point records, checked as
              read
============  ==================================================================================
"""
