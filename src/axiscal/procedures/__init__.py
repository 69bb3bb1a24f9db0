"""axiscal.procedures."""
