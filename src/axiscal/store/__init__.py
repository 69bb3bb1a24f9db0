"""axiscal.store."""
