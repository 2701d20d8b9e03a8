"""Reading scene and study files: ``yaml.safe_load`` semantics, duplicate keys refused.

A file can never run code (only the safe constructors), and a key given twice is reported with
its dotted path instead of silently keeping the last value; every problem is a
:class:`~sweep.io.problems.Problem`, so that a user sees them all at once.
"""
from pathlib import Path

import yaml

from .problems import MISSING, FileProblems, Problem, join_path


def duplicate_keys(node):
    """Problems for every mapping key given twice in a composed YAML node tree, in file order.

    Run it before constructing: construction flattens merge keys (<<) into the nodes.
    """
    return [problem for _, problem in sorted(_duplicates(node, ""), key=lambda lp: lp[0])]


def _duplicates(node, path):
    """(line, Problem) pairs of the duplicate keys below ``node``."""
    found = []
    if isinstance(node, yaml.MappingNode):
        first = {}
        for key_node, value_node in node.value:
            if key_node.tag == "tag:yaml.org,2002:merge":
                continue  # keys merged in by << may be overridden by explicit ones
            key = key_node.value if isinstance(key_node, yaml.ScalarNode) else None
            line = key_node.start_mark.line + 1
            if key is not None and (key_node.tag, key) in first:
                found.append((line, Problem(join_path(path, key), key,
                                            f"duplicate key (first at line "
                                            f"{first[key_node.tag, key]}, again at line {line})")))
            elif key is not None:
                first[key_node.tag, key] = line
            found += _duplicates(value_node, join_path(path, key))
    elif isinstance(node, yaml.SequenceNode):
        for i, item in enumerate(node.value):
            found += _duplicates(item, join_path(path, i))
    return found


class UniqueKeyLoader(yaml.SafeLoader):
    """``yaml.SafeLoader`` that raises :class:`FileProblems` for duplicate keys.

    ``yaml.load(text, Loader=UniqueKeyLoader)`` behaves as ``yaml.safe_load`` otherwise.
    """

    def get_single_data(self):
        node = self.get_single_node()
        if node is None:
            return None
        problems = duplicate_keys(node)
        if problems:
            raise FileProblems(problems)
        return self.construct_document(node)


def parse_yaml(text):
    """Parse YAML text, returning ``(data, problems)``.

    Duplicate keys are problems (the data keeps the last value, so that the rest of the file can
    still be checked); a syntax error is a single problem located by line and column and gives
    ``data = None``.
    """
    loader = UniqueKeyLoader(text)
    try:
        node = loader.get_single_node()
        if node is None:
            return None, []
        problems = duplicate_keys(node)
        return loader.construct_document(node), problems
    except yaml.YAMLError as err:
        mark = getattr(err, "problem_mark", None)
        where = f"line {mark.line + 1}, column {mark.column + 1}" if mark else "(file)"
        message = getattr(err, "problem", None) or str(err)
        return None, [Problem(where, MISSING, f"YAML error: {message}")]
    finally:
        loader.dispose()


def read_text(path):
    """Text of a file, or :class:`FileProblems` saying why it cannot be read."""
    try:
        return Path(path).read_text(encoding="utf-8")
    except (OSError, UnicodeDecodeError) as err:
        reason = getattr(err, "strerror", None) or err
        raise FileProblems([Problem("(file)", str(path), f"cannot read: {reason}")], path) from None


def read_yaml(path):
    """Data of a YAML file; raises :class:`FileProblems` for syntax errors or duplicate keys."""
    data, problems = parse_yaml(read_text(path))
    if problems:
        raise FileProblems(problems, path)
    return data


def top_level_problems(data, problems, what, sections):
    """The problem of a file whose content is empty or not a mapping (none if it is one).

    ``data, problems`` come from :func:`parse_yaml`; ``what`` names the file ('scene'),
    ``sections`` its first sections ('body, contact'), for the message.
    """
    if data is None and not problems:
        return [Problem("(file)", MISSING, f"the {what} is empty")]
    if data is not None and not isinstance(data, dict):
        return [Problem("(file)", data, f"a {what} must be a mapping of {sections}, ...")]
    return []
