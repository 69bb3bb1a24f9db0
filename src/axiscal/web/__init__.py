"""The web workbench: ``axiscal serve`` (FastAPI, Jinja2, vendored htmx and uPlot).

:func:`axiscal.web.app.create_app` builds the application; the pages call the same library as the
command line (``io`` readers, ``standards`` evaluations, ``store`` history, ``compensation``
writers) and render. No calculation lives here.
"""
