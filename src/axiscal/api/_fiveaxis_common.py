"""What the five-axis API modules share (:mod:`axiscal.api.fiveaxis`,
:mod:`axiscal.api.fiveaxis_ballbar`): the configuration as a dict, and the seed checked."""

from __future__ import annotations

from axiscal.errors import InputError

__all__ = ["config_dict", "check_seed"]


def config_dict(config) -> dict:
    """A configuration given as a dict, or read from a TOML path."""
    if isinstance(config, dict):
        return config
    from axiscal.io._files import load_toml

    return load_toml(config)


def check_seed(seed) -> int:
    """A random seed: a whole number >= 0 (InputError otherwise)."""
    if isinstance(seed, bool) or not isinstance(seed, int) or seed < 0:
        raise InputError(f"seed = {seed!r} must be a whole number >= 0")
    return seed
