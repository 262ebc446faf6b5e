"""Safe YAML reading for model files.

PyYAML's safe loader is used (the C one when available, for speed on big files), with
three corrections the file contract asks for (model-format.md, header):

- ``1e6`` and ``2.0e7`` are numbers (YAML 1.1 reads them as strings);
- a key repeated within one mapping is an error (PyYAML keeps the last silently);
- alias expansion is bounded, so an "alias bomb" (billion laughs) is an error instead of
  an exhausted machine.
"""

import gc
import re

import yaml

from ..errors import ModelError

_BaseLoader = getattr(yaml, "CSafeLoader", yaml.SafeLoader)

# Expanded node count above which a document is refused. A 1e5-DOF lattice given in
# YAML has a few 1e5 nodes; aliases that multiply beyond this are an attack or a bug.
MAX_EXPANDED_NODES = 20_000_000

_FLOAT = re.compile(
    r"""^(?:[-+]?(?:[0-9][0-9_]*)\.[0-9_]*(?:[eE][-+]?[0-9]+)?
    |[-+]?(?:[0-9][0-9_]*)(?:[eE][-+]?[0-9]+)
    |\.[0-9_]+(?:[eE][-+][0-9]+)?
    |[-+]?\.(?:inf|Inf|INF)
    |\.(?:nan|NaN|NAN))$""",
    re.X,
)


class _Duplicate(Exception):
    """A mapping repeats a key (found while constructing; explained by _check_graph)."""


class _Loader(_BaseLoader):
    """Safe loader whose float resolver also accepts exponents without a dot or sign, and
    which refuses repeated keys while it constructs (cheap: no second walk of the graph).
    """

    def construct_mapping(self, node, deep=False):
        keys = [k.value for k, _ in node.value
                if isinstance(k, yaml.ScalarNode) and k.value != "<<"]
        if len(keys) != len(set(keys)):
            raise _Duplicate()
        return super().construct_mapping(node, deep)


_Loader.yaml_implicit_resolvers = {
    k: [(tag, rx) for tag, rx in v if tag != "tag:yaml.org,2002:float"]
    for k, v in _BaseLoader.yaml_implicit_resolvers.items()
}
_Loader.add_implicit_resolver("tag:yaml.org,2002:float", _FLOAT, list("-+0123456789."))


# Every cranefe file (model, scene, sweep) has the top-level key 'cranefe'. A file
# without it is refused before its content can appear in a message, so a scene naming
# '/etc/shadow' as its model never echoes a line of it (docs/security.md).
_CRANEFE = re.compile(r"(?:^|[{,\s])['\"]?cranefe['\"]?\s*:")
NOT_CRANEFE = ("not a cranefe model file: it has no 'cranefe: 1' entry; if it is a model, "
               "scene or sweep file, start the file with 'cranefe: 1'")


def _path(parent, key):
    """``ropes.hoist.path[2]``-style entry names for messages."""
    if isinstance(key, int):
        return f"{parent}[{key}]"
    return f"{parent}.{key}" if parent else str(key)


def _check_graph(root, file):
    """Reject duplicate keys and alias expansions larger than MAX_EXPANDED_NODES."""
    sizes = {}
    open_ = set()          # nodes whose children are still being sized (recursion)
    stack = [(root, False, "")]
    while stack:
        node, done, where = stack.pop()
        if id(node) in sizes:
            continue
        if not done and id(node) in open_:
            raise ModelError("an alias ('*name') refers to an entry that contains it, so the "
                             "document would be infinite; replace the alias by its value",
                             file, where or None)
        children = []
        if isinstance(node, yaml.MappingNode):
            seen = {}
            for k, v in node.value:
                key = k.value if isinstance(k, yaml.ScalarNode) else "?"
                children += [(k, where), (v, _path(where, key))]
                if isinstance(k, yaml.ScalarNode) and k.value != "<<":
                    if k.value in seen:
                        line = k.start_mark.line + 1
                        inside = f"in '{where}' " if where else "at the top level "
                        raise ModelError(
                            f"key '{k.value}' is repeated {inside}(lines {seen[k.value]} "
                            f"and {line}); YAML keeps only one of them, so delete or "
                            "rename the other", file, f"{_path(where, key)}, line {line}")
                    seen[k.value] = k.start_mark.line + 1
        elif isinstance(node, yaml.SequenceNode):
            children = [(c, _path(where, i)) for i, c in enumerate(node.value)]
        if not done:
            open_.add(id(node))
            stack.append((node, True, where))
            stack.extend((c, False, w) for c, w in children if id(c) not in sizes)
            continue
        total = 1 + sum(sizes.get(id(c), 1) for c, _ in children)
        if total > MAX_EXPANDED_NODES:
            raise ModelError(
                "the document expands (through aliases '*name') to more than "
                f"{MAX_EXPANDED_NODES:,} entries; remove the recursive or repeated aliases",
                file, where or None)
        sizes[id(node)] = total
        open_.discard(id(node))


def read_yaml(path, text=None):
    """Parse one YAML document safely; return ``(data, text)``.

    Raises `ModelError` naming the file (and line) for syntax errors, duplicate keys and
    alias bombs.
    """
    file = str(path)
    if text is None:
        from ..outpaths import note_read
        note_read(path)
        try:
            with open(path, encoding="utf-8") as fh:
                text = fh.read()
        except FileNotFoundError:
            raise ModelError("file not found; check the path", file) from None
        except IsADirectoryError:
            raise ModelError("is a directory, not a model file", file) from None
        except UnicodeDecodeError as exc:
            raise ModelError(f"not UTF-8 text ({exc.reason})", file) from None
        except OSError as exc:
            raise ModelError(f"cannot be read ({exc.strerror})", file) from None
    loader = _Loader(text)
    # The cyclic garbage collector is paused while the document is built: its passes over
    # the growing tree of new objects took 60% of the reading of a 1e5-coordinate lattice
    # (8.2 s of CPU -> 3.2 s). A YAML document holds no reference cycles unless an alias
    # refers to an entry that contains it (refused below when the file has anchors), and
    # anything left is collected once the collector runs again.
    collecting = gc.isenabled()
    gc.disable()
    try:
        node = loader.get_single_node()
        if node is None:
            raise ModelError("the file is empty; a model starts with 'cranefe: 1'", file)
        if "&" in text:            # anchors, so aliases are possible: bound the expansion
            _check_graph(node, file)
        try:
            data = loader.construct_document(node)
        except _Duplicate:
            _check_graph(node, file)      # names the entry and both lines
            raise
    except yaml.MarkedYAMLError as exc:
        if not _CRANEFE.search(text):           # not ours: show none of it
            raise ModelError(NOT_CRANEFE, file, "cranefe") from None
        mark = exc.problem_mark
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else None
        hint = ""
        if mark and "\t" in (text.splitlines()[mark.line:mark.line + 1] or [""])[0]:
            hint = "; indent with spaces, not tabs"
        cm = exc.context_mark
        if exc.context and cm and (not mark or cm.line != mark.line):
            hint += f" ({exc.context} that starts on line {cm.line + 1})"
        raise ModelError(f"YAML syntax error: {exc.problem or exc}{hint}", file,
                         where) from None
    except yaml.reader.ReaderError as exc:
        line = text[:max(exc.position, 0)].count("\n") + 1
        ch = exc.character
        ch = f"#x{ch:04x}" if isinstance(ch, int) else repr(ch)
        raise ModelError(f"character {ch} is not allowed in YAML "
                         "(a control character); delete it", file, f"line {line}") from None
    except yaml.YAMLError as exc:
        raise ModelError(f"YAML error: {exc}", file) from None
    except RecursionError:
        raise ModelError("the document nests too deeply", file) from None
    finally:
        loader.dispose()
        if collecting:
            gc.enable()
    if isinstance(data, dict) and "cranefe" not in data:
        raise ModelError(NOT_CRANEFE, file, "cranefe")
    return data, text
