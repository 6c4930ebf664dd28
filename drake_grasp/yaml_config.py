"""Loading named configurations from YAML files into dataclasses, with one-line errors.

A file holds several named configurations (scenarios, perception settings); Drake's
`yaml_load_typed` reads one of them into a dataclass, over given defaults. Anything wrong with the
file (unreadable, malformed YAML, fields that do not match the schema) becomes a one-line
ValueError that names the file and the configuration, as the command line reports it.
"""

import pathlib

from pydrake.common.yaml import yaml_load_typed


def load_named(schema, filename: str | pathlib.Path, name: str, defaults, what: str):
    """The configuration `name` of `filename` as a `schema` instance, over `defaults`.

    Args:
        schema: the dataclass type.
        filename: the YAML file of named configurations.
        name: which configuration (a top-level key).
        defaults: the instance the file's values override.
        what: what the file holds, for error messages ("scenario", "perception config").

    Raises:
        ValueError: (one line) if the file cannot be read or does not match the schema.
    """
    filename = pathlib.Path(filename)
    try:
        text = filename.read_text()
    except OSError as e:
        raise ValueError(f"{filename}: cannot read {what} file ({e.strerror})") from None
    names = _top_level_names(text)
    if names is None:  # malformed YAML (the typed loader names the line) or not a mapping
        try:
            yaml_load_typed(schema=schema, data=text, child_name=name, defaults=defaults)
        except Exception as e:
            first_line = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
            raise ValueError(f"{filename}: {what} file is malformed: {first_line}") from None
        raise ValueError(f"{filename}: not a {what} file (expected named {what}s at the top level, "
                         "e.g. 'default:')")
    if not names:
        raise ValueError(f"{filename}: the {what} file is empty (expected named {what}s, e.g. 'default:')")
    if name not in names:
        raise ValueError(f"{filename}: no {what} named '{name}' (the file has: {', '.join(names) or 'none'})")
    try:
        return yaml_load_typed(schema=schema, data=text, child_name=name, defaults=defaults)
    except Exception as e:  # yaml_load_typed raises RuntimeError / yaml errors with multi-line text
        first_line = str(e).strip().splitlines()[0] if str(e).strip() else type(e).__name__
        raise ValueError(f"{filename}: {what} '{name}' is malformed: {first_line}") from None


def _top_level_names(text: str) -> list[str] | None:
    """The names of a file of named configurations (its top-level keys; [] for an empty file), or
    None if the text is not a YAML mapping. Malformed YAML gives None too."""
    import yaml

    class Loader(yaml.SafeLoader):  # Drake's tags (!FovDegrees, ...) are read as empty values here
        pass

    Loader.add_multi_constructor("!", lambda loader, suffix, node: None)
    try:
        data = yaml.load(text, Loader=Loader)
    except yaml.YAMLError:
        return None
    if data is None:
        return []
    if not isinstance(data, dict):
        return None
    return [str(k) for k in data]
