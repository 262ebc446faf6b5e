"""Safe YAML reading for model files.

PyYAML's safe loader is used (the C one when available, for speed on big files), with
three corrections the file contract asks for (model-format.md, header):

- ``1e6`` and ``2.0e7`` are numbers (YAML 1.1 reads them as strings);
- a key repeated within one mapping is an error (PyYAML keeps the last silently);
- alias expansion is bounded, so an "alias bomb" (billion laughs) is an error instead of
  an exhausted machine.
"""

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


class _Loader(_BaseLoader):
    """Safe loader whose float resolver also accepts exponents without a dot or sign."""


_Loader.yaml_implicit_resolvers = {
    k: [(tag, rx) for tag, rx in v if tag != "tag:yaml.org,2002:float"]
    for k, v in _BaseLoader.yaml_implicit_resolvers.items()
}
_Loader.add_implicit_resolver("tag:yaml.org,2002:float", _FLOAT, list("-+0123456789."))


def _check_graph(root, file):
    """Reject duplicate keys and alias expansions larger than MAX_EXPANDED_NODES."""
    sizes = {}
    stack = [(root, False)]
    while stack:
        node, done = stack.pop()
        if id(node) in sizes:
            continue
        children = []
        if isinstance(node, yaml.MappingNode):
            seen = {}
            for k, v in node.value:
                children += [k, v]
                if isinstance(k, yaml.ScalarNode) and k.value != "<<":
                    if k.value in seen:
                        line = k.start_mark.line + 1
                        raise ModelError(
                            f"key '{k.value}' is repeated in one mapping (lines "
                            f"{seen[k.value]} and {line}); keep one of them",
                            file, f"line {line}")
                    seen[k.value] = k.start_mark.line + 1
        elif isinstance(node, yaml.SequenceNode):
            children = list(node.value)
        if not done:
            stack.append((node, True))
            stack.extend((c, False) for c in children if id(c) not in sizes)
            continue
        total = 1 + sum(sizes.get(id(c), 1) for c in children)
        if total > MAX_EXPANDED_NODES:
            raise ModelError(
                "the document expands (through aliases) to more than "
                f"{MAX_EXPANDED_NODES:,} entries; remove the recursive or repeated aliases",
                file)
        sizes[id(node)] = total


def read_yaml(path, text=None):
    """Parse one YAML document safely; return ``(data, text)``.

    Raises `ModelError` naming the file (and line) for syntax errors, duplicate keys and
    alias bombs.
    """
    file = str(path)
    if text is None:
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
    try:
        node = loader.get_single_node()
        if node is None:
            raise ModelError("the file is empty; a model starts with 'cranefe: 1'", file)
        _check_graph(node, file)
        data = loader.construct_document(node)
    except yaml.MarkedYAMLError as exc:
        mark = exc.problem_mark
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else None
        raise ModelError(f"YAML syntax error: {exc.problem or exc}", file, where) from None
    except yaml.YAMLError as exc:
        raise ModelError(f"YAML error: {exc}", file) from None
    except RecursionError:
        raise ModelError("the document nests too deeply", file) from None
    finally:
        loader.dispose()
    return data, text
