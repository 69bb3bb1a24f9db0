"""What a machine's history page shows: a page of its tests with their key parameters, the trend
parameter of each axis, its audit trail and the machines it may be merged into (kept by
:func:`axiscal.web.memo.memoised` while the history is unchanged; its rows rendered once per
process while each row's fields are unchanged)."""

from __future__ import annotations

__all__ = ["KEY", "PAGE", "machine_view"]

#: The key parameter of a test: the first of these it has (else its first).
KEY = ("E", "A", "R", "B", "squareness", "straightness")
#: Tests shown on one page of a machine's history (newest first).
PAGE = 100
_KEY = KEY


def machine_view(st, env, machine_id: int, axis: str, kind: str, page: int) -> dict:
    """What a machine's history page shows (kept by :func:`axiscal.web.memo.memoised` while the
    history is unchanged): the page's tests with their key parameters (their rows rendered with
    the templates of ``env``, the same for every user), the trend parameter of each axis, the
    audit trail and the machines it may be merged into."""
    from markupsafe import Markup

    from axiscal.store import queries
    from axiscal.store.corrections import audit
    from axiscal.web.correction_pages import SHOWN

    m = st.machine(machine_id)
    tests = st.tests(machine=m.name, axis=axis or None, kind=kind or None, limit=PAGE + 1,
                     offset=(page - 1) * PAGE, parameters=_KEY)
    newest = tests if page == 1 and not axis and not kind else []
    rows = [(t, _key(t)) for t in tests[:PAGE]]
    return dict(name=m.name, machine_id=m.id, rows_html=Markup(_rows_html(env, rows)),
                trends=_trend_parameters(st, m.name, m.axes, newest), axes=list(m.axes),
                axis=axis, page=page, more=len(tests) > PAGE, total=m.tests,
                audit_entries=audit(st, machine=m.id, limit=SHOWN),
                machines=queries.machine_names(st))


#: Rendered rows of machine pages kept by this process, by everything a row shows (so a row is
#: made again only when one of its fields changes): a write (an upload every few seconds by
#: three people) changes the history's generation and so the page's reads, but only its own row.
_ROWS: dict = {}
_ROWS_KEPT = 20_000


def _rows_html(env, rows) -> str:
    """The rows of a machine's page (``_machine_rows.html``), each rendered once per process
    while its fields are unchanged."""
    template = env.get_template("_machine_rows.html")
    out = []
    for t, key in rows:
        k = (t.id, t.tested_at, t.date_known, t.axis, t.kind, t.filename, t.note, t.withdrawn,
             key)
        html = _ROWS.get(k)
        if html is None:
            if len(_ROWS) >= _ROWS_KEPT:
                _ROWS.clear()
            html = _ROWS[k] = template.render(rows=[(t, key)])
        out.append(html)
    return "".join(out)


def _trend_parameters(st, machine: str, axes, newest=()) -> dict:
    """The parameter a trend of each axis follows: the key parameter of its newest test (E of a
    positioning test, squareness of a ballbar or diagonal test, ...). ``newest``: the machine's
    newest tests, newest first (its first page), where an axis's first is its newest."""
    out = {}
    for a in axes:
        t = next((x for x in newest if x.axis == a), None)
        if t is None:
            found = st.tests(machine=machine, axis=a, limit=1, parameters=_KEY)
            t = found[0] if found else None
        key = _key(t) if t is not None else None
        if key:
            out[a] = key[0]
    return out


def _key(t):
    """The key parameter of a test: the first of :data:`_KEY` it has, else its first (the
    total radial error motion of a five-error test)."""
    for k in _KEY:
        if k in t.parameters:
            return k, t.parameters[k]
    return next(iter(t.parameters.items()), None)
