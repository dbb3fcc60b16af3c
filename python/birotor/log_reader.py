"""Reading LCM log files (lcm-logger's format) without the LCM library.

Each event: u32 sync 0xEDA1DA01 | i64 event number | i64 timestamp [us] |
i32 channel length | i32 data length | channel | data (big-endian).
The reader streams the file and keeps the C++ reader's budget
(transport/log_io.h): regular files only (no FIFO, device or folder), channel
names of 1..63 bytes, event payloads up to 16 MiB. Anything else, a cut event
or a message that does not decode is a LogError naming the file and offset.
"""

import collections
import os
import stat
import struct

SYNC_WORD = 0xEDA1DA01
MAX_CHANNEL_BYTES = 63  # kLogMaxChannelBytes, LCM_MAX_CHANNEL_NAME_LENGTH
MAX_EVENT_DATA_BYTES = 16 << 20  # kLogMaxEventDataBytes [bytes]
_HEADER = struct.Struct(">Iqqii")

LogEvent = collections.namedtuple("LogEvent", "event_number timestamp_us channel data offset", defaults=(0,))


class LogError(ValueError):
    """A log the reader refuses: not a regular file, damaged or cut."""


def _open_regular(path):
    # O_NONBLOCK: opening a FIFO must not wait for a writer; a regular file ignores it.
    try:
        fd = os.open(path, os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY)
    except FileNotFoundError:
        raise LogError(f"{path}: no such file") from None
    except OSError as e:
        raise LogError(f"{path}: {e.strerror}") from None
    if not stat.S_ISREG(os.fstat(fd).st_mode):
        os.close(fd)
        raise LogError(f"{path}: not a regular file (a FIFO, a device or a folder is not a log)")
    return os.fdopen(fd, "rb")


def _check_header(path, offset, sync, channel_bytes, data_bytes):
    if sync != SYNC_WORD:
        raise LogError(f"{path}: no event at offset {offset} (not an LCM log, or damaged)")
    if not 1 <= channel_bytes <= MAX_CHANNEL_BYTES:
        raise LogError(f"{path}: the event at offset {offset} has a channel name of {channel_bytes} bytes "
                       f"(1..{MAX_CHANNEL_BYTES} allowed)")
    if not 0 <= data_bytes <= MAX_EVENT_DATA_BYTES:
        raise LogError(f"{path}: the event at offset {offset} claims {data_bytes} bytes of message "
                       f"(0..{MAX_EVENT_DATA_BYTES} allowed)")


def _channel_name(path, offset, raw):
    if b"\0" in raw:
        raise LogError(f"{path}: the channel name of the event at offset {offset} holds a NUL byte")
    try:
        return raw.decode("utf-8")
    except UnicodeDecodeError:
        raise LogError(f"{path}: the channel name of the event at offset {offset} is not UTF-8") from None


def iter_log(path):
    """Yields every event of the log, reading it piece by piece (memory: one
    event). Raises LogError on a file that is not a log or a damaged one."""
    with _open_regular(path) as f:
        offset = 0
        while True:
            header = f.read(_HEADER.size)
            if not header:
                return
            if len(header) < _HEADER.size:
                raise LogError(f"{path}: the log is cut: {len(header)} bytes at offset {offset} "
                               "are not a whole event header")
            sync, number, timestamp_us, channel_bytes, data_bytes = _HEADER.unpack(header)
            _check_header(path, offset, sync, channel_bytes, data_bytes)
            body = f.read(channel_bytes + data_bytes)
            if len(body) < channel_bytes + data_bytes:
                raise LogError(f"{path}: the log is cut: the event at offset {offset} runs past the end of the file")
            yield LogEvent(number, timestamp_us, _channel_name(path, offset, body[:channel_bytes]),
                           body[channel_bytes:], offset)
            offset += _HEADER.size + len(body)


def message_type_of(data):
    """The generated type whose fingerprint data carries; None when unknown."""
    from . import BY_FINGERPRINT
    return BY_FINGERPRINT.get(bytes(data[:8]))


def decode(data):
    """The message in data, decoded by the type whose fingerprint it carries;
    None for a type this package does not know."""
    message_type = message_type_of(data)
    return None if message_type is None else message_type.decode(data)


def decode_event(path, event, message_type):
    """event's message as message_type; LogError when it does not decode (a
    message cut short or damaged inside an intact event)."""
    try:
        return message_type.decode(event.data)
    except Exception as e:  # struct.error, ValueError, IndexError from lcm-gen's decoder
        raise LogError(f"{path}: the {event.channel} message at offset {event.offset} does not decode as "
                       f"{message_type.__name__} ({len(event.data)} bytes; cut or damaged: {e})") from None


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


class RowMaker:
    """Turns a log's events into rows: log_utime [us], time_s (seconds since
    the log's first event, on the logger's clock: one time base for every
    channel), every field, then one boolean per status bit (named after it)."""

    def __init__(self, path):
        self.path = path
        self.first_utime = None
        self._bits = {}  # message type -> [(name, value)]

    def row(self, event, message_type):
        from . import TYPES
        from .status_bits import decode_status, status_bits
        if self.first_utime is None:
            self.first_utime = event.timestamp_us
        row = {"log_utime": event.timestamp_us, "time_s": (event.timestamp_us - self.first_utime) / 1e6}
        if message_type is None:
            row["bytes"] = len(event.data)
            return row
        flatten(decode_event(self.path, event, message_type), "", row)
        if message_type not in self._bits:
            self._bits[message_type] = status_bits(message_type, TYPES)
        if self._bits[message_type]:
            decode_status(row["status"], self._bits[message_type], row)
        return row


def read_log_rows(path, types=None):
    """{channel: [row dict, ...]} (RowMaker's columns); messages of unknown
    types are kept as their size (column bytes). types (a dict), when given,
    gets each channel's message type (None when unknown)."""
    rows = collections.defaultdict(list)
    maker = RowMaker(path)
    for event in iter_log(path):
        message_type = message_type_of(event.data)
        if types is not None:
            types.setdefault(event.channel, message_type)
        rows[event.channel].append(maker.row(event, message_type))
    return dict(rows)


def read_log(path):
    """{channel: pandas.DataFrame}, one row per message, every field a column;
    each frame's attrs: "units" {column: unit ("" for none)}, "type" (the
    message type's name, "" when unknown), "channel"."""
    import pandas
    from .units import column_unit
    types = {}
    frames = {}
    for channel, rows in read_log_rows(path, types).items():
        frame = pandas.DataFrame.from_records(rows)
        message_type = types.get(channel)
        frame.attrs["units"] = {column: column_unit(message_type, column) for column in frame.columns}
        frame.attrs["type"] = message_type.__name__ if message_type else ""
        frame.attrs["channel"] = channel
        frames[channel] = frame
    return frames
