"""axiscal.compensation."""
