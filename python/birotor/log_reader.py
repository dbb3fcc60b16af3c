"""Reading LCM log files (lcm-logger's format) without the LCM library.

Each event: u32 sync 0xEDA1DA01 | i64 event number | i64 timestamp [us] |
i32 channel length | i32 data length | channel | data (big-endian).
"""

import collections
import struct

SYNC_WORD = 0xEDA1DA01
_HEADER = struct.Struct(">IqqII")

LogEvent = collections.namedtuple("LogEvent", "event_number timestamp_us channel data")


def iter_log(path):
    """Yields every event of the log. Raises ValueError on a damaged log
    (a header that is not an event's, an event cut short)."""
    with open(path, "rb") as f:
        data = f.read()
    at = 0
    while at < len(data):
        if at + _HEADER.size > len(data):
            raise ValueError(f"{path}: {len(data) - at} bytes at offset {at} are not a whole event header")
        sync, number, timestamp_us, channel_len, data_len = _HEADER.unpack_from(data, at)
        if sync != SYNC_WORD:
            raise ValueError(f"{path}: no event at offset {at} (not an LCM log, or damaged)")
        start = at + _HEADER.size
        end = start + channel_len + data_len
        if end > len(data):
            raise ValueError(f"{path}: the event at offset {at} runs past the end of the file")
        yield LogEvent(number, timestamp_us, data[start:start + channel_len].decode("utf-8", "replace"),
                       data[start + channel_len:end])
        at = end


def decode(data):
    """The message in data, decoded by the type whose fingerprint it carries;
    None for a type this package does not know."""
    from . import BY_FINGERPRINT
    message_type = BY_FINGERPRINT.get(bytes(data[:8]))
    return None if message_type is None else message_type.decode(data)


def flatten(message, prefix="", out=None):
    """{column: value} of every field: arrays as name[i], nested types as name.field."""
    out = {} if out is None else out
    for field in message.__slots__:
        _flatten_value(prefix + field, getattr(message, field), out)
    return out


def _flatten_value(name, value, out):
    if isinstance(value, (list, tuple)):
        for i, item in enumerate(value):
            _flatten_value(f"{name}[{i}]", item, out)
    elif hasattr(value, "__slots__"):
        flatten(value, name + ".", out)
    else:
        out[name] = value


def read_log_rows(path, types=None):
    """{channel: [row dict, ...]} with log_utime first in each row; messages of
    unknown types are kept as their size (column bytes). types (a dict), when
    given, gets each channel's message type (None when unknown)."""
    from . import BY_FINGERPRINT
    rows = collections.defaultdict(list)
    for event in iter_log(path):
        message_type = BY_FINGERPRINT.get(bytes(event.data[:8]))
        message = None if message_type is None else message_type.decode(event.data)
        if types is not None:
            types.setdefault(event.channel, message_type)
        row = {"log_utime": event.timestamp_us}
        if message is None:
            row["bytes"] = len(event.data)
        else:
            flatten(message, "", row)
        rows[event.channel].append(row)
    return dict(rows)


def read_log(path):
    """{channel: pandas.DataFrame}, one row per message, every field a column."""
    import pandas
    return {channel: pandas.DataFrame.from_records(rows) for channel, rows in read_log_rows(path).items()}
