"""`pycram schema`: JSON Schemas for editors, generated from the declarations validation uses.

Every shipped world, plan and variation file validates against its schema with the `jsonschema`
library (the standard validator), files validation rejects for a wrong name or value do not,
the schema names every designator, action and query, and the shipped copies in
resources/schemas/ are what the declarations say.
"""
from __future__ import annotations

import json
import re
from pathlib import Path
from typing import Any

import jsonschema
import pytest
import yaml
from click.testing import CliRunner

from pycram_cli.cli.editor_schema import FILE_KINDS, Schemas, build, render
from pycram_cli.cli.main import cli
from pycram_cli.reasoning import QUERIES

REPO = Path(__file__).resolve().parents[2]
SHIPPED = {"world": sorted((REPO / "worlds").glob("*.yaml")),
           "plan": sorted(p for p in (REPO / "plans").glob("*.yaml") if not p.name.endswith(".vary.yaml")),
           "vary": sorted((REPO / "plans").glob("*.vary.yaml"))}
MODELINE = re.compile(r"^# yaml-language-server: \$schema=(\S+)$")


def run(*args: str):
    return CliRunner().invoke(cli, list(args))


def yaml_data(text: str) -> Any:
    """YAML as an editor reads it (YAML 1.2): PyYAML's YAML 1.1 reads an unquoted key `on` as true."""
    def plain(value: Any) -> Any:
        if isinstance(value, dict):
            return {("on" if key is True else key): plain(item) for key, item in value.items()}
        if isinstance(value, list):
            return [plain(item) for item in value]
        return value

    return plain(yaml.safe_load(text))


@pytest.fixture(scope="module")
def validators() -> dict[str, jsonschema.Draft202012Validator]:
    found = {}
    for kind in FILE_KINDS:
        schema = build(kind)
        jsonschema.Draft202012Validator.check_schema(schema)
        found[kind] = jsonschema.Draft202012Validator(schema)
    return found


def problems(validator: jsonschema.Draft202012Validator, text: str) -> list[str]:
    return [f"{'/'.join(map(str, e.absolute_path))}: {e.message[:300]}" for e in validator.iter_errors(yaml_data(text))]


@pytest.mark.parametrize("kind,path", [(kind, path) for kind, paths in SHIPPED.items() for path in paths],
                         ids=lambda value: value.name if isinstance(value, Path) else value)
def test_every_shipped_file_validates_against_its_schema_and_names_it_on_its_first_line(validators, kind, path):
    text = path.read_text()
    assert problems(validators[kind], text) == []
    match = MODELINE.match(text.splitlines()[0])
    assert match, f"{path.name}: the first line is not a yaml-language-server modeline"
    named = (path.parent / match.group(1)).resolve()
    assert named == REPO / "resources" / "schemas" / f"{kind}.schema.json" and named.is_file()


def test_every_kind_of_file_is_shipped():
    assert all(SHIPPED.values())


@pytest.mark.parametrize("kind", list(FILE_KINDS))
def test_the_shipped_schemas_are_what_the_declarations_say(kind):
    shipped = REPO / "resources" / "schemas" / f"{kind}.schema.json"
    assert shipped.read_text() == render(kind), \
        "regenerate with: python -m pycram_cli.cli.editor_schema --write resources/schemas"


@pytest.mark.parametrize("kind", list(FILE_KINDS))
def test_every_declared_key_has_its_value_shape(kind):
    builder = Schemas()
    getattr(builder, kind)()
    assert builder.missing == [], "give these keys a value shape in pycram_cli/cli/editor_schema.py"


@pytest.mark.parametrize("kind,text", [
    ("plan", "body:\n  - movng: {target: [0.65, 0.7, 0]}\n"),                          # unknown designator
    ("plan", "body:\n  - action: transprt\n    object-type: milk\n"),                   # unknown action
    ("plan", "body:\n  - if: {stabel: {object: milk}}\n    then: [{log: x}]\n"),       # unknown query
    ("plan", "body:\n  - moving: {target: [0.65, 0.7]}\n"),                             # a position of two numbers
    ("plan", "body:\n  - moving: {target: [0.65, 0.7, 0], speed: 2}\n"),               # unknown slot
    ("plan", "body:\n  - pick-up: {arm: left}\n"),                                      # a required slot missing
    ("plan", "body:\n  - action: navigate\n    target: {on: table, accessing: h}\n"),   # a location that cannot be
    ("plan", "body:\n  - retry: two\n    body: [{log: x}]\n"),                          # not a count
    ("plan", "body:\n  - try: [{log: x}]\n    catch: {PerceptionFailur: [{log: y}]}\n"),  # unknown failure type
    ("plan", "body:\n  - detecting: {object-type: milk}\n    as: $obj\n"),              # as: with $
    ("plan", "body: []\n"),
    ("plan", "bodies:\n  - log: x\n"),
    ("world", "objects:\n  - {name: milk, type: milk, file: objects/milk.obj}\ngravty: [0, 0, -9.81]\n"),  # unknown key
    ("world", "objects:\n  - {name: milk, type: milk, file: objects/milk.obj, positon: [1, 0, 0]}\n"),
    ("world", "objects:\n  - {name: milk, type: milk, file: objects/milk.obj, position: [1, 0]}\n"),
    ("world", "objects:\n  - {name: milk, file: objects/milk.obj}\n"),
    ("world", "description: no objects and no world it extends\n"),
    ("world", "extends: kitchen\nobjects:\n  - {name: milk, positon: [1, 0, 0]}\n"),
    ("vary", "objects:\n  milk: {nosie: 0.1}\n"),
    ("vary", "objects:\n  milk: {region: {box: [[0, 0, 0], [1, 1, 1]], on: kitchen/sink_area_surface}}\n"),
    ("vary", "params:\n  arm: {range: [0, 1], choose: [1]}\n"),
])
def test_files_validation_rejects_do_not_validate(validators, kind, text):
    assert problems(validators[kind], text), text


@pytest.mark.parametrize("text", [
    "body:\n  - moving: {target: $pose}\n",                                  # a $variable for a position
    "body:\n  - moving: {target: [$x, 0.7, 0], orientation: $o}\n",          # ... or inside one
    "body:\n  - action: navigate\n    target: {reachable-for: $milk, visible-for: $milk}\n",
    "body:\n  - action: transport\n    object-type: $type\n    target: $where\n    as: placed\n",
    "body:\n  - wait: $seconds\n  - fail: $failure\n  - for_each: $items\n    as: i\n    do: {log: $i}\n",
    "params: {target: {type: position, default: [1, 2, 3]}}\nbody:\n  - moving: {target: $target}\n",
    "plans:\n  park: [{move-arm-joints: {left-arm: park}}]\nbody:\n  - call: park\n",
    "body:\n  - if: {not: {equal: [$o, spoon]}}\n    then: [{log: \"$o is not the spoon\"}]\n",
    "body:\n  - retry: 2\n    on: [PerceptionFailure]\n    recover: {looking: {target: [1.3, 1, 0.9]}}\n"
    "    body: [{detecting: {object-type: milk}, as: obj}]\n",
])
def test_variables_and_every_form_validation_accepts_validate(validators, text):
    assert problems(validators["plan"], text) == []


@pytest.mark.parametrize("text", [
    "extends: kitchen\n",
    "extends: kitchen\nobjects:\n  - {name: milk, position: [1.3, 1.1, 0.851]}\n"
    "  - {name: mug, type: mug, file: objects/mug.urdf}\n",
])
def test_a_world_that_extends_another_names_its_objects_changes_by_name_alone(validators, text):
    assert problems(validators["world"], text) == []


def _yaml_blocks(path: Path) -> list[str]:
    return re.findall(r"```yaml\n(.*?)```", path.read_text(), re.S)


def test_the_docs_example_files_validate(validators):
    """The README's and docs/plans.md's complete plan and variation files."""
    checked = 0
    for doc in (REPO / "README.md", REPO / "docs" / "plans.md"):
        for block in _yaml_blocks(doc):
            data = yaml_data(block)
            kind = "plan" if isinstance(data, dict) and "body" in data else (
                "vary" if isinstance(data, dict) and "plan" in data else None)
            if kind:
                assert problems(validators[kind], block) == [], f"{doc.name}:\n{block}"
                checked += 1
    assert checked >= 3


def test_the_schema_names_every_designator_action_and_query_pycram_designators_lists():
    listed = json.loads(run("designators", "--json").stdout)
    text = json.dumps(build("plan"), ensure_ascii=False)
    plan = build("plan")
    step_heads = {head for variant in plan["$defs"]["step"]["anyOf"] for head in variant["required"][:1]}
    actions = {variant["properties"]["action"]["const"] for variant in plan["$defs"]["step"]["anyOf"]
               if "action" in variant["properties"]}
    for entry in listed:
        if entry["level"] == "motion":
            assert entry["type"] in step_heads
            slots = plan["$defs"][f"designator.{entry['type']}"]["properties"]
        else:
            assert entry["type"] in actions
            slots = next(v["properties"] for v in plan["$defs"]["step"]["anyOf"]
                         if v.get("title") == f"action {entry['type']}")
        for slot in entry["slots"]:
            assert slot["name"] in slots and slot["doc"] in slots[slot["name"]]["description"]
        assert entry["doc"] in text
    for name, query in QUERIES.items():
        assert name in step_heads and query.doc in plan["$defs"][f"query.{name}"]["description"]
        assert set(plan["$defs"][f"query.{name}"]["properties"]) == set(query.param_names)


def test_plain_and_json_output_are_the_same_json_and_the_shipped_file():
    for args in (("schema", "plan"), ("schema", "plan", "--json")):
        result = run(*args)
        assert result.exit_code == 0, result.output
        assert json.loads(result.stdout)["$schema"] == "https://json-schema.org/draft/2020-12/schema"
        assert result.stdout == render("plan")


def test_output_file_is_written_and_a_missing_folder_is_an_input_error(tmp_path: Path):
    target = tmp_path / "plan.schema.json"
    result = run("schema", "world", "-o", str(target))
    assert result.exit_code == 0, result.output
    assert json.loads(target.read_text()) == build("world") and result.stdout == ""
    result = run("schema", "world", "-o", str(tmp_path / "missing" / "world.schema.json"))
    assert result.exit_code == 2
    assert "folder" in result.stderr and "does not exist" in result.stderr and "Traceback" not in result.output
    assert not (tmp_path / "missing").exists()


def test_an_unknown_kind_is_an_input_error_with_a_suggestion():
    result = run("schema", "plna")
    assert result.exit_code == 2
    assert "unknown kind of file 'plna'" in result.stderr and "did you mean 'plan'?" in result.stderr
    result = run("schema", "robot", "--json")
    assert result.exit_code == 2 and json.loads(result.stdout)["errors"][0]["suggestion"] == "kinds: world, plan, vary"


def test_an_editor_completing_action_finds_every_action_usable_until_a_name_is_there():
    """yaml-language-server offers the values of `action: ` from the variants that match the step so far:
    each action's variant asks for its required slots only once `action` holds a name."""
    plan = build("plan")
    for variant in plan["$defs"]["step"]["anyOf"]:
        if variant.get("title", "").startswith("action "):
            check = jsonschema.Draft202012Validator({**variant, "$defs": plan["$defs"]})
            assert [e.validator for e in check.iter_errors({"action": None})] == ["const"], variant["title"]
