"""axiscal.physics."""
