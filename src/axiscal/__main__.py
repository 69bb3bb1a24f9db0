"""``python -m axiscal``: the same command line as the ``axiscal`` script."""

if __name__ == "__main__":  # pragma: no cover - exercised through the CLI tests
    import gc

    gc.disable()   # start-up without the cycle collector: see axiscal.cli.main, which resumes it

    from axiscal.cli import main

    main(gc_paused=True)
