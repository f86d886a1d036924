"""Scenes share slider definitions (content/sliders.json) and variants inherit (``"extends"``): no definition
is written twice, references and inheritance resolve as documented, and a reference that does not resolve is
refused naming the scene file, the variant and the slider (server/lessons/scene_files.py). (When the sliders were
first shared, every scene was checked to read exactly as written out in full before: commit 312325b.)"""
from __future__ import annotations

import json
from collections import defaultdict

import pytest

from server.lessons.scene_files import ContentError, resolved_scene
from server.lessons.scenes import CONTENT_DIR, read_scene_documents, scenes

def test_no_slider_definition_is_written_twice_and_every_shared_one_is_used():
    """Two sliders written out in full with the same label are a copy: they belong in content/sliders.json."""
    shared = json.loads((CONTENT_DIR / "sliders.json").read_text(encoding="utf-8"))
    written, used = defaultdict(list), set()
    for path in sorted((CONTENT_DIR / "scenes").glob("*.json")):
        for variant in json.loads(path.read_text(encoding="utf-8"))["variants"]:
            for slider in [*variant.get("sliders", []), *([variant["overlay"]] if variant.get("overlay") else [])]:
                if "use" in slider:
                    used.add(slider["use"])
                else:
                    written[json.dumps(slider["label"], sort_keys=True)].append(f"{path.stem}/{variant['id']}")
    assert {label: where for label, where in written.items() if len(where) > 1} == {}
    assert used == set(shared)


def test_the_equation_of_motion_writes_each_slider_once():
    """Its four motors on one machine: three variants extend the first and every common slider is shared (the
    six-bars too: Whitworth's variant extends the shaping machine's; the free law's variant, driven by a moment given by
    points, extends none)."""
    raw = json.loads((CONTENT_DIR / "scenes" / "equation_of_motion.json").read_text(encoding="utf-8"))
    assert [v.get("extends") for v in raw["variants"]] == [None, "linear", "linear", "linear", None, None, None,
                                                           "shaping", None]
    in_full = [s["id"] for v in raw["variants"] for s in v["sliders"] if "use" not in s]
    assert len(in_full) == len(set(in_full)) == 4          # of its 40 sliders; the 36 others are shared
    motion = scenes()["equation-of-motion"]
    assert [s.id for s in motion.variants[1].sliders] == ["lambda", "f", "load", "omega0", "M_nominal"]
    assert motion.variants[1].request["inertias"] == motion.variants[0].request["inertias"]
    assert motion.variants[1].request["motor"]["kind"] == "induction"
    assert "M0" not in motion.variants[1].request["motor"]     # a request's key is replaced whole, not merged


SHARED = {"ratio": {"id": "lambda", "param": "params.l2", "scale": "params.l1", "min": 1.3, "max": 6,
                    "step": 0.01, "default": 3, "label": {"ru": "λ", "uk": "λ", "en": "λ"}}}


def scene(*variants) -> dict:
    return {"id": "s", "variants": list(variants)}


def test_a_reference_takes_the_shared_definition_with_its_own_keys_replacing():
    out = resolved_scene(scene({"id": "a", "sliders": [{"use": "ratio", "max": 8, "default": 4}]}), "s.json", SHARED)
    assert out["variants"][0]["sliders"] == [SHARED["ratio"] | {"max": 8, "default": 4}]
    assert SHARED["ratio"]["max"] == 6                     # the shared definition itself is untouched


def test_an_inheriting_variant_takes_the_others_keys_and_merges_the_request_by_key():
    base = {"id": "a", "mechanism": "m", "panels": ["p"], "sliders": [{"use": "ratio"}],
            "request": {"load": {"f": 0.1}, "motor": {"kind": "linear", "b": 0.3}}}
    child = {"id": "b", "extends": "a", "request": {"motor": {"kind": "constant"}}}
    grandchild = {"id": "c", "extends": "b", "panels": ["q"]}
    a, b, c = resolved_scene(scene(base, child, grandchild), "s.json", SHARED)["variants"]
    assert b == {"id": "b", "mechanism": "m", "panels": ["p"], "sliders": [SHARED["ratio"]],
                 "request": {"load": {"f": 0.1}, "motor": {"kind": "constant"}}}
    assert c == b | {"id": "c", "panels": ["q"]}
    c["request"]["load"]["f"] = 0.5                        # variants share no objects
    assert a["request"]["load"]["f"] == b["request"]["load"]["f"] == 0.1


@pytest.mark.parametrize("variants, named", [
    ([{"id": "a", "sliders": [{"use": "nothing", "id": "f"}]}], "s.json: variant a, slider f: uses 'nothing'"),
    ([{"id": "a", "overlay": {"use": "nothing"}}], "s.json: variant a, overlay 0: uses 'nothing'"),
    ([{"id": "a", "extends": "z"}], "s.json: variant a: extends 'z', which is no variant of this scene"),
    ([{"id": "a", "extends": "b"}, {"id": "b", "extends": "a"}], "s.json: variant b: extends a in a loop (a → b → a)"),
    ([{"id": "a"}, {"id": "a"}], "s.json: variant a: two variants with this id"),
    ([{"label": {}}], "s.json: variant 0: no id"),
])
def test_a_reference_that_does_not_resolve_is_refused_naming_scene_variant_and_slider(variants, named):
    with pytest.raises(ContentError) as refused:
        resolved_scene(scene(*variants), "s.json", SHARED)
    assert str(refused.value).startswith(named)


def test_a_shared_slider_that_does_not_validate_names_the_scene_variant_and_slider(tmp_path):
    (tmp_path / "scenes").mkdir()
    (tmp_path / "sliders.json").write_text(json.dumps(SHARED))
    variant = {"id": "slider_crank", "sliders": [{"use": "ratio", "min": "small"}]}
    (tmp_path / "scenes" / "lesson.json").write_text(json.dumps(scene(variant)))
    with pytest.raises(ContentError, match=r"^lesson\.json: variant slider_crank, slider lambda: min: "):
        read_scene_documents(tmp_path)
