"""Reading scene and study files: ``yaml.safe_load`` semantics, with the hostile parts refused.

A file can never run code (only the safe constructors), and a key given twice is reported with
its dotted path instead of silently keeping the last value.  These are configuration files, so
more is refused: anchors and aliases (``&name``, ``*name``: a few hundred bytes of them expand
to billions of values), nesting deeper than :data:`MAX_DEPTH`, files larger than
:data:`MAX_TEXT_BYTES` (which also bounds reading ``/dev/zero``), keys that are not strings
(``on:``, ``1:``) and strings holding control characters.  Every problem is a
:class:`~sweep.io.problems.Problem`, so that a user sees them all at once.
"""
import re

import yaml
from yaml.composer import ComposerError
from yaml.constructor import ConstructorError

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


MAX_DEPTH = 64  # levels of nested mappings and lists; our files need five
MAX_TEXT_BYTES = 1_000_000  # our files have a few kB; PyYAML reads some 100 kB a second
_CONTROL = re.compile(r"[\x00-\x08\x0b\x0c\x0e-\x1f\x7f-\x9f]")  # all but tab and newlines


class UniqueKeyLoader(yaml.SafeLoader):
    """``yaml.SafeLoader`` that raises :class:`FileProblems` for duplicate keys, and a located
    YAML error for anchors, aliases, nesting deeper than :data:`MAX_DEPTH` and values that do
    not convert (an integer of thousands of digits, a timestamp of month 13).

    ``yaml.load(text, Loader=UniqueKeyLoader)`` behaves as ``yaml.safe_load`` otherwise.
    """

    _depth = 0

    def compose_node(self, parent, index):
        event = self.peek_event()
        if isinstance(event, yaml.AliasEvent) or event.anchor is not None:
            raise ComposerError(None, None, "anchors (&name) and aliases (*name) are not "
                                "accepted in these files: write each value out",
                                event.start_mark)
        if self._depth >= MAX_DEPTH:
            raise ComposerError(None, None, f"nested deeper than {MAX_DEPTH} levels",
                                event.start_mark)
        self._depth += 1
        try:
            return super().compose_node(parent, index)
        finally:
            self._depth -= 1

    def construct_object(self, node, deep=False):
        try:
            return super().construct_object(node, deep)
        except (ValueError, OverflowError) as err:
            reason = str(err).split(":")[0]
            raise ConstructorError(None, None, f"cannot read this value ({reason})",
                                   node.start_mark) from None

    def get_single_data(self):
        node = self.get_single_node()
        if node is None:
            return None
        problems = duplicate_keys(node)
        if problems:
            raise FileProblems(problems)
        return self.construct_document(node)


def content_problems(data, path=""):
    """Problems of keys that are not strings and of strings with control characters."""
    found = []
    if isinstance(data, dict):
        for key, value in data.items():
            below = join_path(path, str(key))
            if not isinstance(key, str):
                found.append(Problem(below, key, "a key must be a string (quote it: YAML reads "
                                                 "on, off, yes, no and numbers as other types)"))
            found += content_problems(key, below) + content_problems(value, below)
    elif isinstance(data, list):
        for i, item in enumerate(data):
            found += content_problems(item, join_path(path, i))
    elif isinstance(data, str) and _CONTROL.search(data):
        character = _CONTROL.search(data).group()
        found.append(Problem(path or "(file)", data,
                             f"contains the control character U+{ord(character):04X}"))
    return found


def _located(text, err):
    """Where in ``text`` a YAML error is: 'line L, column C', or '(file)'."""
    mark = getattr(err, "problem_mark", None)
    if mark is not None:
        return f"line {mark.line + 1}, column {mark.column + 1}"
    if isinstance(err, yaml.reader.ReaderError) and isinstance(text, str):
        before = text[:err.position].split("\n")
        return f"line {len(before)}, column {len(before[-1]) + 1}"
    return "(file)"


def _message(err):
    if isinstance(err, yaml.reader.ReaderError):
        return f"the character U+{err.character:04X} is not allowed in a YAML file"
    return getattr(err, "problem", None) or str(err)


def parse_yaml(text):
    """Parse YAML text, returning ``(data, problems)``.

    Duplicate keys, keys that are not strings and strings with control characters are problems
    (the data keeps the last value, so that the rest of the file can still be checked); a
    syntax error, anchor, alias or too deep nesting is a single problem located by line and
    column and gives ``data = None``.
    """
    loader = None
    try:
        loader = UniqueKeyLoader(text)
        node = loader.get_single_node()
        if node is None:
            return None, []
        problems = duplicate_keys(node)
        data = loader.construct_document(node)
        return data, problems + content_problems(data)
    except yaml.YAMLError as err:
        return None, [Problem(_located(text, err), MISSING, f"YAML error: {_message(err)}")]
    finally:
        if loader is not None:
            loader.dispose()


def read_text(path):
    """Text of a file of at most :data:`MAX_TEXT_BYTES`, or :class:`FileProblems` saying why it
    cannot be read."""
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_TEXT_BYTES + 1)
        if len(data) > MAX_TEXT_BYTES:
            raise FileProblems([Problem("(file)", str(path), f"larger than {MAX_TEXT_BYTES} "
                                        "bytes: give long axes as {start, stop, num}")], path)
        return data.decode("utf-8")
    except (OSError, UnicodeDecodeError) as err:
        reason = getattr(err, "strerror", None) or err
        raise FileProblems([Problem("(file)", str(path), f"cannot read: {reason}")], path) from None


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
