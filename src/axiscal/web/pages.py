"""The workbench's pages: plan a test (no database needed), and the history pages."""

from __future__ import annotations

from fastapi import FastAPI, Request
from fastapi.responses import HTMLResponse

from axiscal.errors import InputError
from axiscal.web.inputs import checked_form, form_number
from axiscal.web.rendering import download, query, render
from axiscal.web.login import login_routes

__all__ = ["add_routes", "plan_from_form"]

_PLAN_FIELDS = ("kind", "travel", "targets", "step", "runs", "feed")


def add_routes(app: FastAPI) -> None:
    """Every route of the workbench."""
    login_routes(app)
    from axiscal.web import history_pages

    history_pages.add_routes(app)
    from axiscal.web import signoff_pages

    signoff_pages.add_routes(app)
    from axiscal.web import laboratory_pages

    laboratory_pages.add_routes(app)      # the laboratory kept in the history (issue 40)
    from axiscal.web import measured_pages

    measured_pages.add_routes(app)        # a capture, raw readings + log, an archive

    @app.get("/plan", response_class=HTMLResponse)
    async def plan_page(request: Request):
        form = {"kind": "linear", "travel": "", "targets": "", "step": "", "runs": "5", "feed": ""}
        return render(request, "plan.html", "Plan a test", form=form, controllers=_controllers())

    @app.post("/plan", response_class=HTMLResponse)
    async def plan_make(request: Request):
        form = await checked_form(request)
        values = {k: str(form.get(k, "")).strip() for k in _PLAN_FIELDS}
        try:
            plan = plan_from_form(values)
            _program_feed(values.get("feed"))
        except InputError as exc:
            return render(request, "plan.html", "Plan a test", 400, form=values, error=str(exc),
                          controllers=_controllers())
        return render(request, "plan.html", "Plan a test", form=values,
                      plan=_describe(plan), query=query(**values), controllers=_controllers())

    @app.get("/plan.csv")
    async def plan_csv(request: Request, kind: str = "linear", travel: str = "",
                       targets: str = "", step: str = "", runs: str = "5"):
        plan = plan_from_form({"kind": kind, "travel": travel, "targets": targets,
                               "step": step, "runs": runs})
        return download(plan.to_csv(), f"plan_{kind}_{travel}.csv", "text/csv")

    @app.get("/plan.program")
    async def plan_program(request: Request, controller: str = "linuxcnc", kind: str = "linear",
                           travel: str = "", targets: str = "", step: str = "", runs: str = "5",
                           feed: str = ""):
        """The plan's part program in ``controller``'s language (issue 41): the one writer,
        :func:`axiscal.programs.write_program`, as ``axiscal plan … --program``."""
        from axiscal.programs import MachineOptions, extension, write_program

        plan = plan_from_form({"kind": kind, "travel": travel, "targets": targets,
                               "step": step, "runs": runs})
        text = write_program(plan, controller, MachineOptions(feed=_program_feed(feed)))
        return download(text, f"plan_{kind}_{travel}{extension(controller)}", "text/plain")


def _controllers() -> tuple:
    from axiscal.programs import CONTROLLERS

    return CONTROLLERS


def _program_feed(text) -> float:
    """The form's feed (mm/min or deg/min; blank: 1000)."""
    return form_number(text or "1000", "feed (mm/min or deg/min)", 1e-3, 1e6)


def plan_from_form(values: dict):
    """An ISO 230-2 plan from the form's text fields (the same bounds as ``axiscal plan``)."""
    from axiscal.cli.plan import MAX_LENGTH_MM, MAX_RUNS, MAX_TARGETS, MAX_TRAVEL_DEG
    from axiscal.procedures.positioning import plan_linear, plan_rotary

    kind = values.get("kind", "linear")
    if kind not in ("linear", "rotary"):
        raise InputError(f"axis kind {kind!r}: linear or rotary")
    limit = MAX_LENGTH_MM if kind == "linear" else MAX_TRAVEL_DEG
    travel = form_number(values.get("travel"), "length or travel", 0.0, limit, required=True)
    runs = int(form_number(values.get("runs") or "5", "runs", 1, MAX_RUNS, whole=True))
    if kind == "linear":
        n = values.get("targets")
        n = int(form_number(n, "targets", 2, MAX_TARGETS, whole=True)) if n else None
        return plan_linear(travel, n_targets=n, runs=runs)
    step = values.get("step")
    step = form_number(step, "step", 1e-6, 360.0) if step else None
    if step and travel / step > MAX_TARGETS:
        raise InputError(f"a step of {step:g} deg over {travel:g} deg gives more than "
                         f"{MAX_TARGETS} targets")
    return plan_rotary(travel, step=step, runs=runs)


def _describe(plan) -> str:
    t = plan.targets
    shown = ", ".join(f"{v:g}" for v in t[:12]) + (" …" if t.size > 12 else "")
    return (f"{t.size} targets [{shown}] {plan.target_unit}; {plan.runs} runs, "
            f"{'bidirectional' if plan.bidirectional else 'unidirectional'}, {plan.cycle} cycle; "
            f"{plan.n_measurements} readings")
