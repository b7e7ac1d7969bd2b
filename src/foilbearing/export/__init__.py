"""Export to other rotordynamics tools: ``ross`` builds a ROSS ``BearingElement``."""
