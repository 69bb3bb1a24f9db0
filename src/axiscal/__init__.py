"""axiscal: calibration of machine-tool and turntable axes.

Laser interferometry, reference rotary calibrators, laser scales, ballbars and multi-DOF optical
sensors, evaluated by the ISO 230 family of standards, with faithful simulations of every
instrument and machine.

The package is layered (see the README): ``errors``, ``units``, ``datasets`` -> ``physics`` ->
``standards`` -> ``machines`` -> ``instruments`` -> ``procedures`` -> ``compensation`` ->
``io``/``report``/``store`` -> ``cli``/``web``. A layer imports only from the layers before it.
"""

__version__ = "0.1.0"

__all__ = ["__version__"]
