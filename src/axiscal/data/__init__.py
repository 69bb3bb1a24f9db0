"""Embedded default configurations (the ``axiscal demo`` machines)."""
