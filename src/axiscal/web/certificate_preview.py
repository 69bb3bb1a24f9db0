"""The test page's "certificate preview (DRAFT, PDF)": the certificate the sign-off would issue
now, made by the issue's own calls, never numbered.

The sign-off form starts from the laboratory kept in the history, the machine's last certificate
and the stored test (:func:`axiscal.web.signoff_pages.signoff_context`); the preview takes that
form as it stands, turns it into the job and the laboratory as pressing Issue would
(:func:`~axiscal.web.signoff_pages.job_from_form`, :func:`~axiscal.web.signoff_form.
lab_from_form`, :func:`axiscal.store.laboratory.signoff_config`) and writes the certificate with
:func:`axiscal.report.issue.write_certificate` over the history (its machine, serial, axis as
corrected there), ``preview=True``: a DRAFT naming what is still missing. So the preview and the
issued certificate name the item, the date, the instruments and the laboratory alike (issue 40:
the preview read the user configuration only and the file's names).
"""

from __future__ import annotations

__all__ = ["preview_inputs", "preview_pdf"]


def preview_inputs(st, test_id: int) -> tuple:
    """(stored test, its evaluation named as the history names it, configuration, tolerances,
    rule) of the sign-off as its form stands."""
    from axiscal.report.issue import load_config
    from axiscal.store.laboratory import laboratory, signoff_config
    from axiscal.web.signoff_form import lab_from_form
    from axiscal.web.signoff_pages import job_from_form, signoff_context

    t = st.get(test_id)
    ev = t.named(t.evaluate_again())
    user = load_config(None)
    ctx = signoff_context(st, t, ev, None, "", user)
    job, tolerances, rule, _ = job_from_form(ctx["form"], ctx["parameters"])
    lab = lab_from_form(ctx["form"], laboratory(st), job.get("instrument", []))
    return t, ev, signoff_config(st, t, user, job, lab), tolerances, rule


def preview_pdf(st, t, ev, cfg: dict, tolerances: dict, rule, paper: str) -> bytes:
    """The DRAFT certificate of :func:`preview_inputs`, as PDF bytes."""
    import tempfile
    from pathlib import Path

    from axiscal.report.issue import write_certificate

    with tempfile.TemporaryDirectory() as d:
        path = Path(d) / "certificate.pdf"
        write_certificate(path, ev.dataset, ev.evaluation, cfg, t.raw, tolerances, rule, paper,
                          store=st, filename=t.summary.filename, customer_supplied=(),
                          preview=True)
        return path.read_bytes()
