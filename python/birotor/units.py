"""Units of the message fields: the unit a field's name ends in (utime: us,
_n: N, _rad_s: rad/s, ...), else the last [unit] in its comment in the .lcm
files shipped with the package (birotor/lcmtypes/), else none."""

import os
import re

_LCM_DIR = os.path.join(os.path.dirname(os.path.abspath(__file__)), "lcmtypes")
_SUFFIXES = [("utime", "us"), ("_rad_s2", "rad/s^2"), ("_rad_s", "rad/s"), ("_m_s2", "m/s^2"), ("_m_s", "m/s"),
             ("_rad", "rad"), ("_us", "us"), ("_hz", "Hz"), ("_s", "s"), ("_n", "N"), ("_m", "m")]


def _read_lcm_files():
    units, field_types = {}, {}  # (struct, field) -> unit from the comment, -> field's type name
    if not os.path.isdir(_LCM_DIR):
        return units, field_types
    for name in sorted(os.listdir(_LCM_DIR)):
        if not name.endswith(".lcm"):
            continue
        struct_name, comment = None, ""
        for line in open(os.path.join(_LCM_DIR, name)):
            text = line.strip()
            declaration = re.match(r"([\w.]+)\s+(\w+)\s*(\[[^\]]*\])?\s*;", text)
            if text.startswith("struct"):
                struct_name, comment = text.split()[1], ""
            elif text.startswith("//"):
                comment += " " + text[2:]
            elif struct_name and declaration and declaration.group(1) != "const":
                field = declaration.group(2)
                field_types[(struct_name, field)] = declaration.group(1).split(".")[-1]
                # [N], [rad/s], [1]; not an index such as inputs[0].
                found = [u for u in re.findall(r"\[([^\]\[]+)\]", comment) if u == "1" or not u.isdigit()]
                if found:
                    units[(struct_name, field)] = found[-1]
                comment = ""
            elif not text:
                comment = ""
    return units, field_types


UNITS, _FIELD_TYPES = _read_lcm_files()
# Columns the reader adds before the fields (log_reader.RowMaker).
_READER_COLUMNS = {"log_utime": "us", "time_s": "s"}


def column_unit(message_type, column):
    """Unit of a flattened column of message_type (e.g. "force_n[0]",
    "inputs[2].age_s"); "" when the field has none (a status bit, a count).
    message_type: the generated class, or its name ("force_estimate_t",
    "birotor.force_estimate_t"), or None for a type the package does not know."""
    if column in _READER_COLUMNS:
        return _READER_COLUMNS[column]
    if message_type is None:
        return ""
    type_name = message_type if isinstance(message_type, str) else message_type.__name__
    type_name = type_name.split(".")[-1]
    parts = [re.sub(r"\[\d+\]", "", part) for part in column.split(".")]
    for part in parts[:-1]:  # nested types
        type_name = _FIELD_TYPES.get((type_name, part), "")
    field = parts[-1]
    for suffix, unit in _SUFFIXES:
        if field == suffix or field.endswith(suffix):
            return unit
    return UNITS.get((type_name, field), "")
