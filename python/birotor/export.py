"""birotor-export: one CSV per channel of an LCM log, every field of every
message a column (arrays as name[i], nested types as name.field), after
log_utime (the logger's receive stamp [us]) and time_s (seconds since the
log's first event), with one 0/1 column per status bit named after the bit;
the header carries units ("force_n[0] [N]").

Files stay inside --output-dir: a channel's file name is the channel with
every byte outside [A-Za-z0-9_-] written as %XX ("../x" -> "%2E%2E%2Fx.csv"),
each CSV is written to a new temporary file (O_EXCL, never through an
existing name or link) and renamed over <name>.csv, and a log with more than
--max-channels channels is refused before any file is written.
Exit status: 0 done, 1 a missing, unreadable, damaged or refused log or a
failed write, 2 a bad command line."""

import argparse
import csv
import os
import sys
import tempfile

PROGRAM = "birotor-export"
# Most channels one export writes (one file each). A birotor log has 11
# channels (15 with a multi-arm vehicle); more is a foreign or hostile log.
DEFAULT_MAX_CHANNELS = 64
_SAFE_BYTES = frozenset(b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789_-")


def _file_mode():
    # mkstemp makes 0600 files; a CSV gets what open() would give (0666 & ~umask).
    umask = os.umask(0o022)
    os.umask(umask)
    return 0o666 & ~umask


def error(message, status=1):
    print(f"{PROGRAM}: error: {message}", file=sys.stderr)
    return status


def safe_file_name(channel):
    """channel as a file name that is one name in the folder: bytes outside
    [A-Za-z0-9_-] as %XX (so no "/", no leading "."; one channel, one name)."""
    return "".join(chr(b) if b in _SAFE_BYTES else f"%{b:02X}" for b in channel.encode("utf-8")) + ".csv"


class ChannelCsv:
    """One channel's rows, written to a temporary body file while the log is
    read (columns can grow with variable-length arrays), then the header and
    the body into <name>.csv."""

    def __init__(self, output_dir, channel, message_type):
        self.output_dir, self.channel, self.message_type = output_dir, channel, message_type
        self.path = os.path.join(output_dir, safe_file_name(channel))
        self.columns = {}  # column -> position, in first-seen order
        self.count = 0
        fd, self.body_path = tempfile.mkstemp(prefix=".birotor-export-", suffix=".body", dir=output_dir)
        self.body = os.fdopen(fd, "w", newline="")
        self.writer = csv.writer(self.body)

    def add(self, row):
        for column in row:
            self.columns.setdefault(column, len(self.columns))
        values = [""] * len(self.columns)
        for column, value in row.items():
            values[self.columns[column]] = int(value) if isinstance(value, bool) else value
        self.writer.writerow(values)
        self.count += 1

    def header(self, column_unit):
        header = []
        for column in self.columns:
            unit = column_unit(self.message_type, column)
            header.append(f"{column} [{unit}]" if unit else column)
        return header

    def commit(self, column_unit):
        """Header + body into a new temporary file, renamed over <name>.csv
        (a link at that name is replaced, never followed)."""
        self.body.close()
        fd, temporary = tempfile.mkstemp(prefix=".birotor-export-", suffix=".csv", dir=self.output_dir)
        try:
            os.fchmod(fd, _file_mode())
            with os.fdopen(fd, "w", newline="") as out, open(self.body_path, newline="") as body:
                csv.writer(out).writerow(self.header(column_unit))
                for line in body:
                    out.write(line)
            os.replace(temporary, self.path)
        except OSError:
            os.unlink(temporary)
            raise
        finally:
            os.unlink(self.body_path)

    def abandon(self):
        self.body.close()
        if os.path.exists(self.body_path):
            os.unlink(self.body_path)


def export(log, output_dir, max_channels):
    """Writes the CSVs; {channel: ChannelCsv} committed. Raises LogError for
    a refused log (nothing written then) and OSError for a failed write."""
    import birotor
    from birotor.log_reader import RowMaker, message_type_of
    channels = {}
    try:
        maker = RowMaker(log)
        for event in birotor.iter_log(log):
            target = channels.get(event.channel)
            if target is None:
                if len(channels) == max_channels:
                    raise birotor.LogError(f"{log}: more than {max_channels} channels (the event at offset "
                                           f"{event.offset} opens another); --max-channels N allows more")
                target = ChannelCsv(output_dir, event.channel, message_type_of(event.data))
                channels[event.channel] = target
            target.add(maker.row(event, target.message_type))
        if not channels:
            raise birotor.LogError(f"{log}: no message")
        for channel in sorted(channels):
            channels[channel].commit(birotor.column_unit)
            print(f"{channel}: {channels[channel].count} messages, {len(channels[channel].columns)} columns "
                  f"-> {channels[channel].path}")
    finally:
        for target in channels.values():
            target.abandon()
    return channels


def main(argv=None):
    parser = argparse.ArgumentParser(prog=PROGRAM, description=__doc__.split("\n\n")[0].split(": ", 1)[1])
    parser.add_argument("log", help="LCM log file")
    parser.add_argument("--output-dir", required=True, help="folder for <channel>.csv (made if missing)")
    parser.add_argument("--max-channels", type=int, default=DEFAULT_MAX_CHANNELS, metavar="N",
                        help=f"refuse a log with more than N channels, 1..100000 (default {DEFAULT_MAX_CHANNELS})")
    try:
        import birotor
    except ImportError as e:
        return error(f"the Python package birotor is not installed ({e})")
    parser.add_argument("--version", action="version", version=f"%(prog)s {birotor.__version__}")
    args = parser.parse_args(sys.argv[1:] if argv is None else argv)
    if not 1 <= args.max_channels <= 100000:
        parser.error(f"--max-channels {args.max_channels}: allowed 1..100000")
    if not os.path.lexists(args.log):
        return error(f"{args.log}: no such file")
    try:
        os.makedirs(args.output_dir, exist_ok=True)
        export(args.log, args.output_dir, args.max_channels)
    except birotor.LogError as e:
        return error(str(e))
    except OSError as e:
        return error(f"{e.filename or args.output_dir}: {e.strerror}")
    return 0
