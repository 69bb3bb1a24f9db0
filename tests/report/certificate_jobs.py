"""The job of a certificate with every mandatory item given (ISO/IEC 17025:2017 §7.8.2.1 and
§7.8.4.1: the laboratory, the customer, the item, the conditions, the instruments with their
calibration, the signatory), shared by the certificate tests: :data:`COMPLETE` for a positioning
test (tests/report/test_certificate_issue.py), :data:`KIND_COMPLETE` for the other kinds
(tests/report/test_kind_certificate.py). Tests that change one copy it first."""

from __future__ import annotations

import copy

__all__ = ["COMPLETE", "KIND_COMPLETE"]

#: Every mandatory item of a positioning test's certificate given (it is issued).
COMPLETE = {
    "company": {"name": "Precision Metrology GmbH", "address": ["Messweg 12", "Stuttgart"],
                "code": "PM"},
    "operator": {"name": "J. Keller"},
    "customer": {"name": "Example Machining AG", "address": ["Industriestr. 4", "Esslingen"]},
    "machine": {"maker": "Example", "model": "VMC-800", "serial": "VMC8-0042",
                "location": "Example Machining AG, hall 2"},
    "conditions": {"date": "2026-11-20", "air_temperature": 20.4, "material_temperature": 20.6,
                   "measuring_line": "100 mm above the table centre", "feed": "2000 mm/min",
                   "dwell": "4 s"},
    "instrument": [{"name": "Laser interferometer", "serial": "L-1", "certificate": "C-77",
                    "due": "2027-04-30"}],
    "certificate": {"signatory": "Dr. M. Braun", "signatory_role": "Head of laboratory",
                    "specification": "Contract 4711"},
    "uncertainty": {"e_ve": 0.8, "e_ve_source": "drift check"},
}

def _kind_job() -> dict:
    job = copy.deepcopy({k: v for k, v in COMPLETE.items() if k != "uncertainty"})
    job["conditions"] = {"date": COMPLETE["conditions"]["date"]}
    job["certificate"]["issued"] = "2026-11-25"
    return job


#: The same job for a test of another kind: the date of test its only condition (the
#: temperatures, feed and dwell are a positioning test's, ISO 230-2:2014 §3-§6), no E_VE (an
#: input of a positioning test's budget), and a fixed date of issue.
KIND_COMPLETE = _kind_job()
