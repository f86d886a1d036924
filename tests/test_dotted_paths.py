"""Dotted paths into request bodies (server/lessons/dotted_paths.py): read and written against bodies built by hand."""
from server.lessons.dotted_paths import path_key, path_value, set_path


def test_a_number_indexes_a_list_and_a_name_an_object():
    body = {"masses": {"forces": [{"working": 1000.0}, {"working": 20.0, "k": 0.1}]}, "7": "a name"}
    assert path_value(body, "masses.forces.1.k") == 0.1
    assert path_value(body, "7") == "a name"                 # a digit key of an object stays a name
    assert path_key([1, 2], "1") == 1 and path_key({"1": 2}, "1") == "1"


def test_setting_makes_the_objects_on_the_way_and_changes_nothing_else():
    body = {"masses": {"forces": [{"working": 1000.0}]}}
    set_path(body, "masses.forces.0.k", 0.2)
    set_path(body, "motor.M0", 20.6)
    assert body == {"masses": {"forces": [{"working": 1000.0, "k": 0.2}]}, "motor": {"M0": 20.6}}
