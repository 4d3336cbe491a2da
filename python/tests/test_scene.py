"""Scenes from files, text and dicts: the engine's validation, errors with
their place, and editing."""

from __future__ import annotations

import pytest

import mpdem
from conftest import SCENES, shipped


def test_a_scene_file_is_read_and_named():
    scene = mpdem.Scene.from_file(SCENES / "wave_1d.ron")
    assert scene.name == "wave_1d"
    assert scene.file is not None and scene.file.name == "wave_1d.ron"
    assert scene.get("materials[0].density") == 1000.0


def test_a_scene_file_error_has_its_file_line_and_column(tmp_path):
    path = tmp_path / "bad.ron"
    text = (SCENES / "wave_1d.ron").read_text().replace("dt: 1e-4", "dt: -1e-4")
    assert text != (SCENES / "wave_1d.ron").read_text()
    path.write_text(text)
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_file(path)
    err = caught.value
    line = next(k for k, l in enumerate(text.splitlines(), 1) if "dt: -1e-4" in l)
    assert err.file == str(path)
    assert err.line == line
    assert err.column == text.splitlines()[line - 1].index("-1e-4") + 1
    assert "expected a finite value > 0" in err.message
    assert str(err).startswith(f"{path}:{line}:{err.column}: ")


def test_a_missing_file_is_a_scene_error_naming_it(tmp_path):
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_file(tmp_path / "none.ron")
    assert caught.value.file == str(tmp_path / "none.ron")
    assert "cannot read the scene" in caught.value.message


def test_ron_text_errors_have_line_and_column_but_no_file():
    text = "Scene(\n  grid: (origin: (0, 0), cell_size: 0.1, cells: (2, 2)),\n  time: (dt: 1e-3, end: 1),\n  materials: [(name: \"m\", density: -5.0, model: LinearElastic((youngs_modulus: 1e6, poisson_ratio: 0.3)))],\n)"
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_ron(text)
    err = caught.value
    assert err.file is None
    # The place of the value refused.
    assert (err.line, err.column) == (4, text.splitlines()[3].index("-5.0") + 1)
    assert "density" in err.message


def test_a_syntax_error_has_its_place():
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_ron("Scene(\n  grid: (origin: (0, 0),\n")
    assert caught.value.line is not None


def test_every_shipped_scene_reads_back_from_its_dict_and_its_ron():
    scenes = sorted(SCENES.glob("*.ron"))
    assert len(scenes) >= 20
    for path in scenes:
        scene = mpdem.Scene.from_file(path)
        d = scene.to_dict()
        assert mpdem.Scene.from_dict(d, folder=SCENES).to_dict() == d, path
        assert mpdem.Scene.from_ron(scene.to_ron(), folder=SCENES).to_dict() == d, path


def test_a_dict_error_of_type_names_its_key_path():
    d = shipped("granular_collapse_bui").to_dict()
    d["time"]["dt"] = "fast"
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_dict(d)
    assert caught.value.key_path == "time.dt"
    assert str(caught.value).startswith("time.dt: ")


def test_a_dict_error_of_validation_names_its_key_path():
    d = shipped("granular_collapse_bui").to_dict()
    d["bodies"][0]["material"] = "granite"
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_dict(d)
    assert caught.value.key_path == "bodies[0].material"
    assert "unknown material 'granite'" in caught.value.message
    assert (caught.value.file, caught.value.line) == (None, None)


def test_a_material_parameter_error_is_placed_at_the_model():
    d = shipped("granular_collapse_bui").to_dict()
    d["materials"][0]["model"]["DruckerPrager"]["friction_angle"] = 95.0
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_dict(d)
    assert caught.value.key_path == "materials[0].model"
    assert "friction_angle must be in [0, 90)" in caught.value.message


def test_a_scene_is_not_a_list():
    with pytest.raises(mpdem.SceneError, match="a scene is a dict"):
        mpdem.Scene.from_dict([1, 2])


def test_an_edit_is_validated_and_a_refused_one_changes_nothing():
    scene = shipped("granular_collapse_bui")
    scene.set("materials[rods].model.DruckerPrager.friction_angle", 30.0)
    assert scene.get("materials[0].model.DruckerPrager.friction_angle") == 30.0
    before = scene.to_dict()
    with pytest.raises(mpdem.SceneError) as caught:
        scene.set("bodies[column].points_per_cell", 0)
    assert caught.value.key_path == "bodies[0].points_per_cell"
    assert scene.to_dict() == before


def test_the_dict_holds_lists_to_edit_in_place():
    scene = shipped("wave_1d")
    d = scene.to_dict()
    assert d["grid"]["cells"] == [200, 2] and isinstance(d["grid"]["origin"], list)
    scene.set("grid.cells[0]", 240)
    assert scene.get("grid.cells") == [240, 2]


def test_a_dict_error_at_the_root_has_no_key_path():
    d = shipped("wave_1d").to_dict()
    del d["grid"]
    with pytest.raises(mpdem.SceneError) as caught:
        mpdem.Scene.from_dict(d)
    assert caught.value.key_path is None
    assert str(caught.value) == "missing field `grid`"


def test_bad_key_paths_are_refused():
    scene = shipped("wave_1d")
    with pytest.raises(KeyError):
        scene.get("materials[3]")
    with pytest.raises(KeyError):
        scene.get("materials[granite]")
    with pytest.raises(KeyError):
        scene.get("nothing")
    for bad in ["", "a..b", "a[", "a[]", "a]b", "[0]x"]:
        with pytest.raises(ValueError, match="not a key path"):
            scene.get(bad)


def test_entries_are_found_by_any_name():
    d = shipped("wave_1d").to_dict()
    first = dict(d["materials"][0], name="1")
    second = dict(d["materials"][0], name="sand.v2", density=2000.0)
    d["materials"] = [first, second]
    d["bodies"][0]["material"] = "1"
    scene = mpdem.Scene.from_dict(d)
    # Quoted, a name; bare digits, a position.
    assert scene.get('materials["sand.v2"].density') == 2000.0
    assert scene.get('materials["1"].density') == 1000.0
    assert scene.get("materials[1].density") == 2000.0


def test_a_serialized_scene_with_optional_fields_reads_back():
    scene = shipped("geostatic_column")
    scene.set("time.max_steps", 1_000_000)
    scene.set("stages[surcharge].edges", {"left": "Free"})
    assert scene.get("stages[surcharge].edges") == {"left": "Free"}
    again = mpdem.Scene.from_ron(scene.to_ron(), folder=SCENES)
    assert again.to_dict() == scene.to_dict()
    scene.set("time.end", 21.0)  # edits still validate the whole scene


def test_an_error_that_names_its_field_names_it_once():
    scene = shipped("wave_1d")
    with pytest.raises(mpdem.SceneError) as caught:
        scene.set("output.frame_interval", -1.0)
    assert caught.value.key_path == "output.frame_interval"
    assert str(caught.value).count("output.frame_interval") == 1


def test_scenes_pickle_copy_and_compare_by_their_fields():
    import copy
    import pickle

    scene = shipped("granular_collapse_bui")
    for again in [pickle.loads(pickle.dumps(scene)), copy.deepcopy(scene), copy.copy(scene)]:
        assert again == scene and again is not scene
        assert again.to_dict() == scene.to_dict()
    other = copy.deepcopy(scene)
    other.set("materials[rods].model.DruckerPrager.friction_angle", 25.0)
    assert other != scene
    assert scene.get("materials[0].model.DruckerPrager.friction_angle") == 19.8
    assert scene != "a scene"
