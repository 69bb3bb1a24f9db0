"""Issue 40, defect 6: "Show the verdict" and the report by every standard name the machine and
axis as the history keeps them (renamed), not as the data file gave them. (The certificate
preview against the issued certificate: tests/web/test_signoff_history.py, the amendment.)"""

from __future__ import annotations

from tests.web.test_signoff_history import JOB_FORM, LAB_FORM, _sign, bench  # noqa: F401


def test_verdict_plot_and_standards_report_use_the_historys_names(bench):  # noqa: F811
    from axiscal.store.corrections import rename_axis, rename_machine

    st = bench.app.state.store
    rename_machine(st, "MCU1025 bench", "ESS test stand", by="A. Operator", reason="site name")
    rename_axis(st, "ESS test stand", "IOC_TEST:AXIS1-POSSET", "X", by="A. Operator",
                reason="the machine's axis letter")
    verdict = _sign(bench, "verdict", **LAB_FORM, **JOB_FORM).text
    assert "positioning deviations, X axis" in verdict and "AXIS1-POSSET axis" not in verdict
    standards = bench.get("/tests/1/standards.html").text
    assert "ESS test stand" in standards and "IOC_TEST:AXIS1-POSSET" not in standards
