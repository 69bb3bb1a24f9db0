"""axiscal.compensation.controllers."""
