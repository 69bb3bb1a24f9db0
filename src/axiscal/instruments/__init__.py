"""axiscal.instruments."""
