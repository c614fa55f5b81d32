"""Pipeline config: YAML reading, schema validation with defaults, the physical checks of
``vines.pipeline.config_checks`` and cross-key rules; every error is one line naming the key.

``python -m vines.pipeline.config FILE`` checks a config file without running anything
(Snakemake itself reports a YAML syntax error in a ``--configfile`` without its line)."""
from __future__ import annotations

import copy
import math
import re

from ..core.params import PARAM_NAMES
from .axes import ConfigError, axis_values, grid_axes
from .config_checks import check_physical


def _with_defaults(validator_class):
    validate_properties = validator_class.VALIDATORS["properties"]

    def set_defaults(validator, properties, instance, schema):
        if isinstance(instance, dict):
            for prop, sub in properties.items():
                if "default" in sub and prop not in instance:
                    instance[prop] = copy.deepcopy(sub["default"])
        yield from validate_properties(validator, properties, instance, schema)

    import jsonschema
    # an integer key takes ints only (JSON Schema also counts 16.0 as an integer, which the
    # pipeline would then use as a float: chunk sizes, thread and block counts)
    strict_int = validator_class.TYPE_CHECKER.redefine(
        "integer", lambda checker, x: isinstance(x, int) and not isinstance(x, bool))
    return jsonschema.validators.extend(validator_class, {"properties": set_defaults},
                                        type_checker=strict_int)


#: a run or entry name: one safe path segment (the schema's definitions.name, matched on
#: the whole string here: a regex search with '$' would accept a trailing newline)
NAME = re.compile(r"[A-Za-z0-9_-][A-Za-z0-9_.-]{0,63}")


def check_names(config, schema: dict, path: str = "") -> None:
    """Every key the schema constrains by ``propertyNames`` (entry names) and ``run`` must
    be one safe path segment: outputs stay under results/<run>/."""
    if path == "" and isinstance(config.get("run"), str) and not NAME.fullmatch(config["run"]):
        raise ConfigError("run", f"{config['run']!r} is not allowed: a run name is 1-64 "
                                 "letters, digits, '_', '-' or '.', not starting with '.'")
    if not isinstance(config, dict) or not isinstance(schema, dict):
        return
    props = schema.get("properties", {})
    extra = schema.get("additionalProperties")
    for key, value in config.items():
        where = f"{path}.{key}" if path else str(key)
        if "propertyNames" in schema and not NAME.fullmatch(str(key)):
            shown = repr(str(key)) if len(str(key)) <= 40 else repr(str(key)[:37]) + "..."
            raise ConfigError(path or "<top level>",
                              f"entry name {shown} ({len(str(key))} characters) is not allowed: "
                              "1-64 letters, digits, '_', '-' or '.', not starting with '.'")
        sub = props.get(key, extra if isinstance(extra, dict) else None)
        if sub is not None:
            check_names(value, sub, where)


#: the config schema, shipped inside the package (the defaults of ``api_defaults`` are
#: filled in when it is loaded)
SCHEMA_FILE = "config.schema.yaml"


def api_defaults() -> dict:
    """Schema defaults that are the API's own, taken from ``core.params`` (the dataclass
    defaults of ``ModelParams`` and ``SolverSettings``, the sweep constants) and not written
    in the schema file: dotted property path ('*': every entry of a named section) ->
    value. ``core.params`` loads no numba: the Snakefile reads the schema at parse time."""
    from dataclasses import fields

    from ..core import params as P
    model = {f.name: f.default for f in fields(P.ModelParams)}
    run = {f.name: f.default for f in fields(P.SolverSettings)}
    out = {"model.r": model["r"]}
    out |= {f"simulation.{k}": run[k]
            for k in ("t_end", "t_transient", "v_stick", "max_impacts", "root_tol")}
    out |= {"sweeps.*.t_settle": P.T_SETTLE_DEFAULT, "sweeps.*.t_step": P.T_STEP_DEFAULT,
            "sweeps.*.n_record": P.N_RECORD_DEFAULT, "sweeps.*.v_stick": run["v_stick"]}
    return out


def _fill_defaults(schema: dict) -> dict:
    """``schema`` with the defaults of ``api_defaults`` filled in (a default already in
    the file would be a second source: refused)."""
    for path, value in api_defaults().items():
        node = schema
        for part in path.split("."):
            node = node["additionalProperties"] if part == "*" else node["properties"][part]
        if "default" in node:
            raise ValueError(f"config schema: {path} has a default of its own; it comes from "
                             "vines.core.params (pipeline.config.api_defaults)")
        node["default"] = value
    return schema


def load_schema(path=None) -> dict:
    """The config schema: the package's own (default) or the file at ``path``, with the
    API's defaults (``api_defaults``)."""
    import yaml
    if path is None:
        from importlib.resources import files
        return _fill_defaults(yaml.safe_load(files(__package__).joinpath(SCHEMA_FILE)
                                             .read_text()))
    with open(path) as fh:
        return _fill_defaults(yaml.safe_load(fh))


def _strict_loader():
    """A yaml SafeLoader that refuses a key given twice in one mapping."""
    import yaml

    class StrictLoader(yaml.SafeLoader):
        def construct_mapping(self, node, deep=False):
            seen = set()
            for key_node, _ in node.value:
                key = self.construct_object(key_node, deep=deep)
                if key in seen:
                    raise yaml.constructor.ConstructorError(
                        None, None, f"key {key!r} given twice", key_node.start_mark)
                seen.add(key)
            return super().construct_mapping(node, deep=deep)

    return StrictLoader


def load_yaml(path) -> dict:
    """Read a YAML config file; a syntax error or a repeated key is a ConfigError naming
    the file and line."""
    import yaml
    try:
        with open(path) as fh:
            data = yaml.load(fh, Loader=_strict_loader())  # noqa: S506 (a SafeLoader)
    except OSError as err:
        raise ConfigError(str(path), f"cannot be read ({err.strerror})") from None
    except yaml.YAMLError as err:
        mark = getattr(err, "problem_mark", None)
        where = f"{path}:{mark.line + 1}:{mark.column + 1}" if mark else str(path)
        problem = getattr(err, "problem", None) or str(err).splitlines()[0]
        raise ConfigError(where, f"YAML syntax error: {problem}") from None
    if not isinstance(data, dict):
        raise ConfigError(str(path), "must hold a mapping of config keys")
    return data


def resolve_point_references(config: dict) -> None:
    """Replace every convergence point given as {timehistory: NAME, index: I} by that point
    of the time-history entry (its eta, omega, F and the reference's label), in place."""
    histories = config.get("timehistories", {})
    for study in ("window", "vstick"):
        points = config.get("convergence", {}).get(study, {}).get("points", [])
        for i, pt in enumerate(points):
            if "timehistory" not in pt:
                continue
            key = f"convergence.{study}.points[{i}]"
            name, k = pt["timehistory"], pt["index"]
            if name not in histories:
                raise ConfigError(f"{key}.timehistory", f"{name!r} is not a timehistories "
                                  f"entry ({sorted(histories)})")
            source = histories[name]["points"]
            if k >= len(source):
                raise ConfigError(f"{key}.index", f"{k} is beyond the {len(source)} point(s) "
                                  f"of timehistories.{name}")
            resolved = {d: source[k][d] for d in ("eta", "omega", "F")}
            if "label" in pt:
                resolved["label"] = pt["label"]
            points[i] = resolved


def _yaml_number_hint(err) -> str:
    """How to write a number the schema refused for its type: one YAML read as text (YAML
    1.1 wants a dot and a signed exponent: 1e30, 1.0e30 and 1e+30 are strings, 1.0e+30 is a
    number), or 16.0 for an integer."""
    if err.validator != "type":
        return ""
    if isinstance(err.instance, float) and err.instance.is_integer():
        return f" (write {int(err.instance)})"
    if not isinstance(err.instance, str):
        return ""
    try:
        value = float(err.instance)
    except ValueError:
        return ""
    if not math.isfinite(value):
        return ""
    if "integer" in str(err.validator_value) and value.is_integer():
        written = str(int(value))
    else:
        mantissa, e, exponent = repr(value).partition("e")      # repr signs the exponent
        written = mantissa + ("" if "." in mantissa else ".0") + e + exponent
    return f" (YAML reads {err.instance} as text: write {written})"


def move_chunk_size(config) -> str | None:
    """Move the deprecated top-level ``chunk_size`` (a valid one; the schema reports any
    other) to ``chunks.simulate_grid``; the one-line note to show, or None without it.
    Both keys given with different values: ConfigError."""
    size = config.get("chunk_size") if isinstance(config, dict) else None
    if not isinstance(size, int) or isinstance(size, bool) or size < 1:
        return None
    chunks = config.setdefault("chunks", {})
    if not isinstance(chunks, dict):
        return None
    if chunks.setdefault("simulate_grid", size) != size:
        raise ConfigError("chunk_size", f"{size} is deprecated and differs from "
                          f"chunks.simulate_grid = {chunks['simulate_grid']}: remove it")
    del config["chunk_size"]
    return (f"vines pipeline: note: config key chunk_size is deprecated; write chunks: "
            f"{{simulate_grid: {size}}} instead (read as that now)")


def validate_config(config: dict, schema: dict) -> dict:
    """Validate ``config`` in place (filling defaults) and check cross-key rules.

    Raises ConfigError naming the first offending key (dotted path).
    """
    import jsonschema
    if isinstance(config, dict):
        check_names(config, schema)      # before the schema: one clear line for a bad name
    move_chunk_size(config)              # the deprecated key (its note: the caller's call)
    cls = _with_defaults(jsonschema.validators.validator_for(schema))
    errors = sorted(cls(schema).iter_errors(config), key=lambda e: list(e.absolute_path))
    if errors:
        err = min(errors, key=lambda e: -len(e.absolute_path))
        key = ".".join(str(p) for p in err.absolute_path) or "<top level>"
        raise ConfigError(key, err.message + _yaml_number_hint(err))
    resolve_point_references(config)
    check_physical(config)   # every value through the API's validators (t_transient < t_end)
    for name, grid in config["grids"].items():
        axes = grid_axes(grid, key=f"grids.{name}")
        for dim, vals in grid.get("sections", {}).items():
            if dim not in grid.get("axes", {}):
                raise ConfigError(f"grids.{name}.sections.{dim}", f"{dim} is fixed in this "
                                  "grid: a section runs along one of its axes "
                                  f"({sorted(grid.get('axes', {}))})")
            missing = [v for v in vals if float(v) not in set(axes[dim].tolist())]
            if missing:
                raise ConfigError(f"grids.{name}.sections.{dim}",
                                  f"{missing} not on the {dim} axis (add them with 'include')")
    for name, sw in config["sweeps"].items():
        if sw["outer"] == sw["param"]:
            raise ConfigError(f"sweeps.{name}.outer", "must differ from param")
        need = set(PARAM_NAMES) - {sw["param"], sw["outer"]}
        if set(sw["fixed"]) != need:
            raise ConfigError(f"sweeps.{name}.fixed", f"must give exactly {sorted(need)}")
        axis_values(sw["values"], key=f"sweeps.{name}.values")
        axis_values(sw["outer_values"], key=f"sweeps.{name}.outer_values")
    for name, br in config["branches"].items():
        need = set(PARAM_NAMES) - {br["param"]}
        if set(br["fixed"]) != need:
            raise ConfigError(f"branches.{name}.fixed", f"must give exactly {sorted(need)}")
    for name, sm in config["stability_maps"].items():
        axis_values(sm["eta"], key=f"stability_maps.{name}.eta")
        axis_values(sm["omega"], key=f"stability_maps.{name}.omega")
    return config


def main(argv=None) -> int:
    """Check config files: ``python -m vines.pipeline.config FILE...`` (exit 2 if invalid)."""
    import sys
    args = sys.argv[1:] if argv is None else argv
    schema = load_schema()
    status = 0
    for path in args:
        try:
            validate_config(load_yaml(path), schema)
            print(f"{path}: valid")
        except ConfigError as err:
            print(f"vines pipeline: {path}: {err}", file=sys.stderr)
            status = 2
    return status


if __name__ == "__main__":
    raise SystemExit(main())
