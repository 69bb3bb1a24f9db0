"""The workbench's plan page offers the part program beside the CSV (issue 41): the download is
the writer's text for the plan the form describes (:func:`axiscal.programs.write_program`, what
``axiscal plan … --program`` writes), and a bad controller or feed is one error page."""

import html
import re

from fastapi.testclient import TestClient

from axiscal.procedures.positioning import plan_rotary
from axiscal.programs import CONTROLLERS, MachineOptions, write_program
from axiscal.web.app import create_app


def test_plan_page_offers_each_controllers_program(tmp_path):
    c = TestClient(create_app(f"sqlite:///{tmp_path / 'h.sqlite'}"), base_url="http://127.0.0.1")
    token = re.search(r'csrf-token" content="([^"]+)"', c.get("/plan").text).group(1)
    r = c.post("/plan", data={"csrf": token, "kind": "rotary", "travel": "360", "step": "45",
                              "runs": "2", "feed": "3600"})
    assert r.status_code == 200
    links = [html.unescape(h) for h in re.findall(r'href="(/plan\.program\?[^"]+)"', r.text)]
    assert [re.search(r"controller=(\w+)", h).group(1) for h in links] == list(CONTROLLERS)
    for h in links:
        d = c.get(h)
        assert d.status_code == 200
        controller = re.search(r"controller=(\w+)", h).group(1)
        want = write_program(plan_rotary(360, step=45, runs=2), controller,
                             MachineOptions(feed=3600.0))
        assert d.text == want
        assert "attachment" in d.headers["content-disposition"]
    bad = c.get("/plan.program?controller=okuma&kind=linear&travel=800")
    assert bad.status_code == 400 and "okuma" in bad.text
    bad = c.get("/plan.program?controller=fanuc&kind=linear&travel=800&feed=0")
    assert bad.status_code == 400 and "feed" in bad.text
