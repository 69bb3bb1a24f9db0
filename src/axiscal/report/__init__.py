"""axiscal.report."""
