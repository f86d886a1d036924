"""No wasted work: each endpoint computes what the request asks for and nothing else.

The core functions are wrapped to count their calls (in this process: the heavy pool off); what the answer
holds is checked against the same quantities computed another way."""
from __future__ import annotations

import numpy as np
import pytest
from fastapi.testclient import TestClient

from server.api import endpoints_forces
from server.runtime import heavy
from server.api.app import create_app
from server.core.elastic import report as elastic_report
from server.core.kinetostatics.crank_slider import Loads, Pairs, analyse
from server.core.kinetostatics.report import crank_check
from server.core.kinetostatics.virtual_work import reduced_moment
from server.lessons.requests import scene_request
from server.lessons.scenes import scenes

API = "/api/v1"
ENGINE = {"params": {"l1": 0.1, "l2": 0.4, "a2": 0.3},
          "loads": {"m2": 3, "J_S2": 0.05, "m3": 2, "omega": 50, "force": 1000, "return_factor": 0.2}}


@pytest.fixture
def client(monkeypatch) -> TestClient:
    monkeypatch.setenv("MDL_CACHE_BYTES", "0")                 # every request computed
    monkeypatch.setattr(heavy, "HEAVY_PROCESSES", 0)           # in this process, where the counters are
    return TestClient(create_app())


def counted(monkeypatch, module, name: str) -> list:
    """Replace module.name by a wrapper that records each call's arguments."""
    calls, original = [], getattr(module, name)

    def wrapper(*args, **kwargs):
        calls.append((args, kwargs))
        return original(*args, **kwargs)
    monkeypatch.setattr(module, name, wrapper)
    return calls


def belt(outputs: list[str]) -> dict:
    scene = scenes()["elastic-transmission"]
    return scene_request(scene, scene.variants[0]) | {"outputs": outputs, "t_end": 0.3, "n": 61}


def test_the_rigid_start_up_is_computed_only_when_rigid_is_asked_for(client, monkeypatch):
    rigid_runs = counted(monkeypatch, elastic_report, "rigid")
    plain = client.post(f"{API}/elastic?precision=full", json=belt(["histories"])).json()
    assert rigid_runs == [] and "rigid" not in plain
    both = client.post(f"{API}/elastic?precision=full", json=belt(["histories", "rigid"])).json()
    assert len(rigid_runs) == 1 and both["t"] == plain["t"] and both["omega"] == plain["omega"]
    assert len(both["rigid"]["omega"]) == len(both["t"])


def test_the_rigid_machine_alone_needs_no_elastic_run_and_is_the_same_start_up(client, monkeypatch):
    """Asked alone, the rigid start-up is sampled on t = 0 … t_end in n points, the histories' times when they
    run to the end: the same numbers as beside the histories."""
    elastic_runs = counted(monkeypatch, elastic_report, "integrate")
    alone = client.post(f"{API}/elastic?precision=full", json=belt(["rigid"])).json()
    assert elastic_runs == [] and set(alone) == {"rigid", "warnings"}
    both = client.post(f"{API}/elastic?precision=full", json=belt(["histories", "rigid"])).json()
    assert both["t"] == np.linspace(0.0, 0.3, 61).tolist()
    assert alone["rigid"] == both["rigid"]


def test_forces_without_friction_analyse_once_and_check_against_the_separate_frictionless_analysis(client, monkeypatch):
    """Without friction in the pairs the analysis is the frictionless one: computed once, and the check (3.2)
    equals the one from a separate frictionless analysis."""
    analyses = counted(monkeypatch, endpoints_forces, "analyse")
    data = client.post(f"{API}/forces?precision=full", json=ENGINE).json()
    assert len(analyses) == 1
    loads = Loads(**{**ENGINE["loads"], "gravity": True})
    phi = np.linspace(0.0, 2 * np.pi, 361)
    params = {"l1": 0.1, "l2": 0.4, "a2": 0.3, "e": 0.0}
    analysis = analyse(params, loads, Pairs(r14=0.02, r12=0.015, r23=0.01), phi, 1e-9)
    separate = crank_check(analysis, analyse(params, loads, Pairs(), phi),
                           reduced_moment(params, analysis.applied, phi))
    assert data["crank_check"] == separate
    rough = client.post(f"{API}/forces", json=ENGINE | {"pairs": {"f12": 0.1}}).json()
    assert len(analyses) == 3 and rough["crank_check"]["with_friction"] > data["crank_check"]["with_friction"]


def test_wear_analyses_the_forces_once(client, monkeypatch):
    analyses = counted(monkeypatch, endpoints_forces, "analyse")
    body = {"params": {"l1": 0.045, "l2": 0.18, "a2": 0.38},
            "loads": {"m2": 1.8, "m3": 1.33, "J1": 0.09, "gas": {"kind": "indicator", "p_max": 3e6,
                                                                   "piston_diameter": 0.075}}}
    assert client.post(f"{API}/wear", json=body).status_code == 200
    assert len(analyses) == 1


def test_the_bearing_iteration_runs_no_rigid_start_up(client, monkeypatch):
    rigid_runs = counted(monkeypatch, elastic_report, "rigid")
    scene = scenes()["elastic-linkage"]
    body = scene_request(scene, scene.variants[1]) | {"outputs": ["bearings"], "t_end": 0.2, "n": 41}
    data = client.post(f"{API}/elastic", json=body).json()
    assert data["bearings"]["rounds"] and rigid_runs == []
