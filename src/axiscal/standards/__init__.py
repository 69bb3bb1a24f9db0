"""axiscal.standards."""
