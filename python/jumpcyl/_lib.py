"""The compiled extension, errors, and small helpers shared by the modules."""
import math

from ._jumpcyl import ffi, lib

# GSL's default error handler aborts the process; the library reports GSL's
# failures as statuses and asks its callers to switch that handler off
# (jumpcyl.h). A process-wide setting, made once on import.
lib.gsl_set_error_handler_off_for_jumpcyl()

ERR_LEN = 1024


class Error(RuntimeError):
    """A failure of the library that is not bad input: a numerical method
    failed (JC_ENUMERIC), a bound was hit (JC_ELIMIT), memory ran out.
    .status is the library's status code, .status_text its name."""

    def __init__(self, message, status=None):
        super().__init__(message)
        self.status = status
        self.status_text = text(lib.jc_status_text(status)) if status is not None else None


def text(p):
    """A C string as str; None for NULL."""
    return None if p == ffi.NULL else ffi.string(p).decode()


def err_buf():
    return ffi.new("char[]", ERR_LEN)


def raise_status(status, err, what=None):
    msg = ffi.string(err).decode(errors="replace") if err is not None else ""
    if not msg:
        msg = text(lib.jc_status_text(status))
    if what:
        msg = "%s: %s" % (what, msg)
    if status == lib.JC_EINVAL:
        raise ValueError(msg)
    if status == lib.JC_ENOMEM:
        raise MemoryError(msg)
    raise Error(msg, status)


def check(status, err, what=None):
    if status != lib.JC_OK:
        raise_status(status, err, what)


def num(v):
    """A double as the tool's JSON holds it: None for NaN and infinities (cJSON prints null)."""
    return v if math.isfinite(v) else None


def name_arg(name):
    """A parameter or option name as Python writes it (rod_offset) or as the tool does (rod-offset)."""
    return name.replace("_", "-")
