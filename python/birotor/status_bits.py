"""The bits of a message's status field, by name: the STATUS_* constants of
the type that defines them in the .lcm files (ESTIMATOR_STATUS carries the
newest FORCE's bits, CONTROLLER_STATUS the newest MOTOR_COMMAND's)."""

# Type whose STATUS_* constants name the bits of another type's status field
# (the field comments of estimator_status_t.lcm and controller_status_t.lcm).
_BITS_DEFINED_BY = {"estimator_status_t": "force_estimate_t", "controller_status_t": "motor_command_t"}


def status_bits(message_type, types):
    """[(name, value), ...] of the single-bit STATUS_* constants naming the
    bits of message_type's status field, lowest bit first; [] when the type
    has no status field or no constants for it. types: {type name: class}."""
    if message_type is None or "status" not in getattr(message_type, "__slots__", ()):
        return []
    owner = types.get(_BITS_DEFINED_BY.get(message_type.__name__, ""), message_type)
    bits = [(name, value) for name, value in vars(owner).items()
            if name.startswith("STATUS_") and isinstance(value, int) and value > 0 and value & (value - 1) == 0]
    return sorted(bits, key=lambda bit: bit[1])


def decode_status(status, bits, row):
    """Adds one boolean per bit (column = the bit's name) to row."""
    for name, value in bits:
        row[name] = bool(status & value)
