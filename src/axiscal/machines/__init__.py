"""Simulated machines: axes with known error functions, the truth a simulation measures against.

Every simulated quantity is SI (metres, radians, seconds). Randomness comes only from an explicit
``numpy.random.Generator`` passed by the caller.
"""
