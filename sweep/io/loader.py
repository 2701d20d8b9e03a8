"""The one loader of every input file: scene, study, bodies and risk files.

:func:`load_file` reads a YAML file (or takes a dict), refuses what is not a mapping and
validates one pydantic model, whose validators do every check of the file, the cross-field
ones included; every problem is reported at once as :class:`~sweep.io.problems.FileProblems`.
The validators find the file's folder (``base_dir``) and its name (``source``) in the
validation context, beside what the caller adds.
"""
from pathlib import Path

from pydantic import ValidationError

from .problems import FileProblems, validation_problems
from .yamlio import parse_yaml, read_text, top_level_problems


def load_file(source, model, what, sections, names, *, text=None, base_dir=None, context=None,
              dotted=None, tags=None, despite_syntax=False):
    """The validated ``model`` of a file.

    Parameters
    ----------
    source : str, Path or dict
        A YAML file, or a dict of the same schema.
    model : type of pydantic.BaseModel
    what, sections : str
        The file's kind ('scene') and first sections ('body, contact'), for the message of a
        file that is not a mapping.
    names : sequence of str
        Every field name of the file's models, for "did you mean".
    text : str, optional
        The file's text, when already read.
    base_dir : str or Path, optional
        Folder that relative paths start from; default the file's folder (a dict: the working
        directory).
    context : dict, optional
        More of the validation context.
    dotted, tags
        As :func:`~sweep.io.problems.validation_problems` takes them.
    despite_syntax : bool
        Validate a mapping with duplicate keys or bad characters too (its last values), so
        that their problems show with the model's.

    Raises
    ------
    FileProblems
        Every problem, with its dotted path and the value given.
    """
    if isinstance(source, dict):
        raw, problems, name = source, [], None
        base_dir = Path(".") if base_dir is None else base_dir
    else:
        name = str(source)
        raw, problems = parse_yaml(read_text(source) if text is None else text)
        base_dir = Path(source).parent if base_dir is None else base_dir
    problems += top_level_problems(raw, problems, what, sections)
    if isinstance(raw, dict) and (despite_syntax or not problems):
        try:
            checked = model.model_validate(raw, context={"base_dir": base_dir, "source": name,
                                                         **(context or {})})
        except ValidationError as err:
            problems += validation_problems(err, names, dotted, tags)
    if problems:
        raise FileProblems(problems, name)
    return checked
