"""The sequence file's YAML, read strictly from libyaml's events: one document of mappings, lists
and scalars, typed as the core types a parameter file (decimal integers and reals, true/false,
null; 0x10, 1_000 or 1:30 stay text and are refused where a number is expected). Anchors, aliases,
tags, several documents and duplicate keys are errors, and the nesting is bounded while the events
stream, so that no input costs much more than its size: an alias bomb expands exponentially,
libyaml's parser is quadratic in flow nesting and PyYAML's C composer recurses on the C stack (a
file of 200,000 '[' crashes it)."""
import math
import re

import yaml

MAX_DEPTH = 32
MAX_INTEGER_DIGITS = 18

_INT = re.compile(r"[-+]?[0-9]+")
_REAL = re.compile(r"[-+]?(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][-+]?[0-9]+)?")
_SPECIAL = {".nan": math.nan, ".inf": math.inf, "+.inf": math.inf, "-.inf": -math.inf}
_NULL = {"", "~", "null", "Null", "NULL"}
_BOOL = {"true": True, "True": True, "TRUE": True, "false": False, "False": False, "FALSE": False}
_LOADER = getattr(yaml, "CSafeLoader", yaml.SafeLoader)


class YamlError(Exception):
    """A message that starts with LINE:COLUMN (1-based) and names the key where known."""


def where(path) -> str:
    """sequence.grids[1].n from ['sequence', 'grids', 1, 'n']."""
    out = ""
    for p in path:
        if not isinstance(p, int) and len(p) > 60:
            p = f"<a key of {len(p)} characters>"
        out += f"[{p}]" if isinstance(p, int) else (("." if out else "") + p)
    return out


def _at(event, path, problem) -> YamlError:
    mark = event.start_mark
    key = where(path)
    return YamlError(f"{mark.line + 1}:{mark.column + 1}: {key + ': ' if key else ''}{problem}")


def _scalar(event, path):
    text = event.value
    if not event.implicit[0]:  # quoted or a block scalar: text
        return text
    if text in _NULL:
        return None
    if text in _BOOL:
        return _BOOL[text]
    if _INT.fullmatch(text):
        if len(text.lstrip("+-")) > MAX_INTEGER_DIGITS:
            raise _at(event, path, f"an integer of {len(text.lstrip('+-'))} digits is out of range")
        return int(text)
    if _REAL.fullmatch(text):
        value = float(text)
        if math.isinf(value):
            raise _at(event, path, f"{text} overflows a double")
        if value == 0 and any(c in "123456789" for c in text.lower().split("e")[0]):
            raise _at(event, path, f"{text} underflows a double")
        return value
    if text.lower() in _SPECIAL:
        return _SPECIAL[text.lower()]
    return text


def load(text: str):
    """The document's value: dicts (keys are text), lists, str, int, float, bool, None."""
    stack = []  # frames [container, path, pending key, {key: line}]
    result, documents = None, 0
    try:
        for ev in yaml.parse(text, Loader=_LOADER):
            if isinstance(ev, (yaml.StreamStartEvent, yaml.StreamEndEvent, yaml.DocumentEndEvent)):
                continue
            path = _path_here(stack)
            if isinstance(ev, yaml.DocumentStartEvent):
                documents += 1
                if documents > 1:
                    raise _at(ev, [], "several YAML documents: expected one")
                continue
            if isinstance(ev, yaml.AliasEvent) or getattr(ev, "anchor", None):
                raise _at(ev, path, "anchors and aliases (& and *) are not allowed in a sequence file")
            if getattr(ev, "tag", None):
                raise _at(ev, path, f"YAML tag {ev.tag} is not interpreted: the type comes from the key")
            if isinstance(ev, (yaml.SequenceEndEvent, yaml.MappingEndEvent)):
                value = stack.pop()[0]
            elif isinstance(ev, (yaml.SequenceStartEvent, yaml.MappingStartEvent)):
                if stack and isinstance(stack[-1][0], dict) and stack[-1][2] is None:
                    raise _at(ev, path, "a key must be a name, not a list or a mapping")
                if len(stack) >= MAX_DEPTH:
                    raise _at(ev, path[:1], f"nested deeper than {MAX_DEPTH} levels")
                stack.append([[] if isinstance(ev, yaml.SequenceStartEvent) else {}, path, None, {}])
                continue
            else:
                frame = stack[-1] if stack else None
                if frame is not None and isinstance(frame[0], dict) and frame[2] is None:
                    key = ev.value
                    if key in frame[3]:
                        raise _at(ev, frame[1] + [key], f"duplicate key (first on line {frame[3][key]})")
                    frame[3][key] = ev.start_mark.line + 1
                    frame[2] = key
                    continue
                value = _scalar(ev, path)
            if not stack:
                result = value
            elif isinstance(stack[-1][0], list):
                stack[-1][0].append(value)
            else:
                stack[-1][0][stack[-1][2]] = value
                stack[-1][2] = None
    except yaml.MarkedYAMLError as e:
        mark = e.problem_mark or e.context_mark
        problem = " ".join(filter(None, (e.context, e.problem)))
        prefix = f"{mark.line + 1}:{mark.column + 1}: " if mark is not None else ""
        raise YamlError(f"{prefix}not valid YAML: {problem}")
    except yaml.YAMLError as e:
        raise YamlError(f"not valid YAML: {' '.join(str(e).split())}")
    return result


def _path_here(stack):
    """The key path of the next value: the pending key of a mapping, the next index of a list."""
    if not stack:
        return []
    container, path, key, _ = stack[-1]
    if isinstance(container, list):
        return path + [len(container)]
    return path + [key] if key is not None else path
