"""``python -m axiscal``: the same command line as the ``axiscal`` script."""

from axiscal.cli import main

if __name__ == "__main__":  # pragma: no cover - exercised through the CLI tests
    main()
