"""A source's table as data (content/tables) and the pickers it gives a scene: Chaika–Vasylenko's Table 1.1 of
wear intensities, each picker row's value the geometric mean of its printed range, and the loader writing a
toggle that names a picker out in full (or refusing it, naming the scene file and the variant)."""
import json
import math

import pytest

from server.lessons.scene_files import ContentError, resolved_scene
from server.lessons.scenes import CONTENT_DIR, scenes

TABLE = json.loads((CONTENT_DIR / "tables" / "wear_intensity.json").read_text(encoding="utf-8"))


def test_each_rows_value_is_the_middle_of_its_printed_decades():
    """The value a picker sets is √(low·high) of the printed range to two significant digits (one printed value
    is its own middle)."""
    for key, row in TABLE["rows"].items():
        low, high = row["range"]
        assert row["value"] == float(f"{math.sqrt(low * high):.2g}"), key
        assert {"ru", "uk", "en"} <= set(row["label"])


def test_the_wear_scene_offers_the_books_example_by_default_and_table_1_1_beside_it():
    toggles = {t.id: t for t in scenes()["wear"].variants[1].toggles}
    assert {key: t.default for key, t in toggles.items()} == \
        {"pin": 0.6e-10, "bush": 1.0e-10, "piston": 2e-12, "cylinder": 3e-12}      # §4.3's intensities
    assert all(t.display == "select" and t.param == f"I_{key}" for key, t in toggles.items())
    assert 4e-10 in toggles["bush"].options                                            # bronze bush, Table 1.1


def variant(toggle) -> dict:
    return {"id": "s", "variants": [{"id": "v", "toggles": [toggle]}]}


def test_a_picker_reference_is_written_out_with_its_own_keys_replacing():
    tables = {"t": {"rows": {"a": {"value": 1.0, "label": {"en": "A"}}, "b": {"value": 2.0, "label": {"en": "B"}}},
                    "pickers": {"p": {"param": "x", "default": "b", "label": {"en": "P"}, "rows": ["a", "b"]}}}}
    out = resolved_scene(variant({"table": "t", "picker": "p", "id": "mine"}), "s.json", {}, {}, tables)
    assert out["variants"][0]["toggles"] == [{"id": "mine", "param": "x", "label": {"en": "P"}, "options": [1.0, 2.0],
                                              "option_labels": [{"en": "A"}, {"en": "B"}], "default": 2.0,
                                              "display": "select"}]
    with pytest.raises(ContentError, match="s.json: variant v: toggle q: content/tables has no picker 'q'"):
        resolved_scene(variant({"table": "t", "picker": "q"}), "s.json", {}, {}, tables)
    tables["t"]["rows"]["b"]["value"] = 1.0
    with pytest.raises(ContentError, match="two rows with one value"):
        resolved_scene(variant({"table": "t", "picker": "p"}), "s.json", {}, {}, tables)
