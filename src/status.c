/* Status codes, messages and the version. */
#include "internal.h"

#include <stdio.h>

const char *jc_version(void) { return JC_VERSION_STRING; }

const char *jc_status_text(int status)
{
    switch (status) {
    case JC_OK: return "ok";
    case JC_EINVAL: return "invalid input";
    case JC_ELIMIT: return "iteration limit reached";
    case JC_ENUMERIC: return "numerical failure";
    case JC_ENOMEM: return "out of memory";
    case JC_ESTOPPED: return "stopped by the recorder";
    default: return "unknown status";
    }
}

int jc_fail(char *err, size_t err_len, int status, const char *fmt, ...)
{
    if (err && err_len > 0) {
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(err, err_len, fmt, ap);
        va_end(ap);
    }
    return status;
}
