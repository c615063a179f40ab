"""Builds jumpcyl._jumpcyl, the cffi extension (API mode) on libjumpcyl.

The declarations cffi reads (its "cdef") are made here from the library's
own public headers, so they cannot drift from them: the headers are run
through the C preprocessor with empty stand-ins for the system headers, and
the integer and floating-point macros named JC_* are added as constants.
The extension is then compiled against the real headers, so the compiler
checks every struct's layout and every function's signature against them.

Where the library is:
  JUMPCYL_BUILD_DIR   a build tree of the repository (libjumpcyl.so there,
                      the headers in ../include beside python/, or
                      JUMPCYL_INCLUDE_DIR)
  JUMPCYL_INCLUDE_DIR, JUMPCYL_LIB_DIR   explicit directories
  otherwise           pkg-config jumpcyl (an installed library), then the
                      repository's build/ next to python/.
"""
import os
import re
import shlex
import subprocess
import sys
import sysconfig
import tempfile

from cffi import FFI

HERE = os.path.dirname(os.path.abspath(__file__))
HEADERS = ("jumpcyl/jumpcyl.h", "jumpcyl/study.h", "jumpcyl/track.h")


def _pkg_config(*args):
    try:
        out = subprocess.run(["pkg-config", *args, "jumpcyl"], check=True, capture_output=True, text=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    return shlex.split(out.stdout)


def locate():
    """(include_dirs, library_dirs): where the headers and libjumpcyl.so are."""
    inc, lib = os.environ.get("JUMPCYL_INCLUDE_DIR"), os.environ.get("JUMPCYL_LIB_DIR")
    build = os.environ.get("JUMPCYL_BUILD_DIR")
    repo_include = os.path.join(HERE, os.pardir, "include")
    if build:
        lib = lib or build
        inc = inc or repo_include
    if inc and lib:
        return [os.path.abspath(inc)], [os.path.abspath(lib)]
    cflags, libs = _pkg_config("--cflags"), _pkg_config("--libs")
    if cflags is not None and libs is not None:
        incs = [f[2:] for f in cflags if f.startswith("-I")]
        libdirs = [f[2:] for f in libs if f.startswith("-L")]
        return incs, libdirs
    repo_build = os.path.join(HERE, os.pardir, "build")
    if os.path.exists(os.path.join(repo_build, "libjumpcyl.so")):
        return [os.path.abspath(repo_include)], [os.path.abspath(repo_build)]
    sys.exit("jumpcyl: libjumpcyl not found: build it (make build) and set JUMPCYL_BUILD_DIR, "
             "or install it (make install) so that pkg-config finds jumpcyl")


def _find_header(include_dirs, name):
    for d in include_dirs + ["/usr/local/include", "/usr/include"]:
        if os.path.exists(os.path.join(d, name)):
            return d
    sys.exit("jumpcyl: %s not found in %s" % (name, include_dirs))


def _preprocess(include_dir, extra):
    """The headers' declarations, preprocessed without the system headers,
    and the -dM list of macros."""
    cc = shlex.split(sysconfig.get_config_var("CC") or "cc")[:1] or ["cc"]
    with tempfile.TemporaryDirectory() as tmp:
        for fake in ("stddef.h", "stdint.h", "stdio.h"):
            open(os.path.join(tmp, fake), "w").close()
        src = os.path.join(tmp, "all.h")
        with open(src, "w") as f:
            f.write("".join('#include <%s>\n' % h for h in HEADERS))
        base = cc + ["-E", "-nostdinc", "-I", tmp, "-I", include_dir, "-D__attribute__(x)=", *extra, src]
        decls = subprocess.run(base[:2] + ["-P"] + base[2:], check=True, capture_output=True, text=True).stdout
        macros = subprocess.run(base[:2] + ["-dM"] + base[2:], check=True, capture_output=True, text=True).stdout
    return decls, macros


_INT = re.compile(r"^[()\s\d*+\-uUlL]+$")
_FLOAT = re.compile(r"^[()\s\d.eE*+\-/]+$")


def _constants(macros):
    """JC_* macros as cdef constants: integers as '#define N ...', others as
    'static const double N;' (cffi takes both values from the compiler)."""
    out = []
    for line in macros.splitlines():
        m = re.match(r"#define (JC_\w+) (.+)$", line)
        if not m or m.group(1) in ("JC_API",):
            continue
        name, value = m.group(1), m.group(2).strip()
        if _INT.match(value) or re.match(r"^JC_\w+$", value):
            out.append("#define %s ..." % name)
        elif _FLOAT.match(value):
            out.append("static const double %s;" % name)
    return "\n".join(out)


# What the Python layer adds in C: a sample table filler (the library's
# column table, jc_sample_value) and a study row collector that keeps each
# case's CSV row and outcome while the study runs without the GIL; its
# progress callback is Python's (it checks for Ctrl-C).
# The row collector, declared to cffi and defined in C from this one text.
ROWS_STRUCT = """\
typedef struct {
    char *csv; size_t csv_len, csv_cap;
    jc_CaseOutcome *outcomes; double *values; long count, cap; int nvalues;
    jc_Tally *tally;
    int keep_outcomes; int failed;
    void *pyctx;
} jcpy_Rows;
"""

HELPERS_CDEF = """
void jcpy_sample_matrix(const jc_Sample *samples, int n, double *out);
""" + ROWS_STRUCT + """int jcpy_rows_init(jcpy_Rows *r, long expected, int nvalues, int keep_outcomes, jc_Tally *tally);
void jcpy_rows_free(jcpy_Rows *r);
int jcpy_study_run(const jc_StudyDef *def, long first, long count, jcpy_Rows *rows, int with_progress,
                   char *err, size_t err_len);
int jcpy_design_run(jc_DesignDef *def, jc_DesignResult *out, void *pyctx, int with_progress,
                    char *err, size_t err_len);
int jcpy_track_fit(const jc_Setup *setup, const jc_Track *t, jc_TrackFitOptions *o, const jc_SimOptions *sim,
                   jc_TrackFitResult *out, void *pyctx, int with_progress, char *err, size_t err_len);
extern "Python" int _jcpy_study_progress(void *pyctx, long done, long count);
extern "Python" int _jcpy_design_progress(void *pyctx, const jc_DesignProgress *p);
extern "Python" int _jcpy_fit_progress(void *pyctx, const jc_TrackFitProgress *p);
void gsl_set_error_handler_off_for_jumpcyl(void);
"""

HELPERS_SOURCE = r"""
#include <jumpcyl/jumpcyl.h>
#include <jumpcyl/study.h>
#include <jumpcyl/track.h>
#include <gsl/gsl_errno.h>
#include <stdlib.h>
#include <string.h>

/* The Python callbacks (extern "Python" in the cdef), defined by cffi after this code. */
static int _jcpy_study_progress(void *pyctx, long done, long count);
static int _jcpy_design_progress(void *pyctx, const jc_DesignProgress *p);
static int _jcpy_fit_progress(void *pyctx, const jc_TrackFitProgress *p);

/* GSL's default handler aborts the process; the library asks its callers
 * to switch it off (jumpcyl.h). */
void gsl_set_error_handler_off_for_jumpcyl(void) { gsl_set_error_handler_off(); }

/* out: n rows of the sample columns, in the table's order (row-major). */
void jcpy_sample_matrix(const jc_Sample *samples, int n, double *out)
{
    const int cols = jc_sample_column_count();
    for (int i = 0; i < n; ++i)
        for (int c = 0; c < cols; ++c) out[(size_t)i * (size_t)cols + (size_t)c] = jc_sample_value(&samples[i], c);
}

""" + ROWS_STRUCT + """
int jcpy_rows_init(jcpy_Rows *r, long expected, int nvalues, int keep_outcomes, jc_Tally *tally)
{
    memset(r, 0, sizeof *r);
    r->nvalues = nvalues;
    r->keep_outcomes = keep_outcomes;
    r->tally = tally;
    r->cap = expected > 0 ? expected : 1;
    r->csv_cap = (size_t)r->cap * 160 + 1;
    r->csv = malloc(r->csv_cap);
    if (keep_outcomes) {
        r->outcomes = malloc((size_t)r->cap * sizeof *r->outcomes);
        r->values = malloc((size_t)r->cap * (size_t)(nvalues > 0 ? nvalues : 1) * sizeof *r->values);
    }
    if (!r->csv || (keep_outcomes && (!r->outcomes || !r->values))) return JC_ENOMEM;
    r->csv[0] = '\0';
    return JC_OK;
}

void jcpy_rows_free(jcpy_Rows *r)
{
    free(r->csv);
    free(r->outcomes);
    free(r->values);
    memset(r, 0, sizeof *r);
}

static int grow(void **p, size_t *cap, size_t need, size_t elem)
{
    if (need <= *cap) return 0;
    size_t n = *cap * 2 > need ? *cap * 2 : need;
    void *q = realloc(*p, n * elem);
    if (!q) return -1;
    *p = q;
    *cap = n;
    return 0;
}

static int on_row(void *ctx, const jc_StudyRow *row)
{
    jcpy_Rows *r = ctx;
    size_t cap = r->csv_cap;
    if (grow((void **)&r->csv, &cap, r->csv_len + (size_t)row->csv_len + 1, 1) != 0) goto nomem;
    r->csv_cap = cap;
    memcpy(r->csv + r->csv_len, row->csv, (size_t)row->csv_len);
    r->csv_len += (size_t)row->csv_len;
    r->csv[r->csv_len] = '\0';
    if (r->keep_outcomes) {
        size_t ocap = (size_t)r->cap, vcap = (size_t)r->cap;
        if (grow((void **)&r->outcomes, &ocap, (size_t)r->count + 1, sizeof *r->outcomes) != 0) goto nomem;
        const size_t nv = (size_t)(r->nvalues > 0 ? r->nvalues : 1);
        if (grow((void **)&r->values, &vcap, (size_t)r->count + 1, nv * sizeof *r->values) != 0) goto nomem;
        r->cap = (long)(ocap < vcap ? ocap : vcap);
        r->outcomes[r->count] = *row->outcome;
        for (int j = 0; j < r->nvalues; ++j) r->values[(size_t)r->count * nv + (size_t)j] = row->values[j];
    }
    if (r->tally && jc_tally_add(r->tally, row->outcome) != JC_OK) goto nomem;
    r->count++;
    return 0;
nomem:
    r->failed = JC_ENOMEM;
    return 1;
}

static int on_progress(void *ctx, long done, long count)
{
    jcpy_Rows *r = ctx;
    return _jcpy_study_progress(r->pyctx, done, count);
}

int jcpy_study_run(const jc_StudyDef *def, long first, long count, jcpy_Rows *rows, int with_progress,
                   char *err, size_t err_len)
{
    jc_StudyCallbacks cb = {on_row, with_progress ? on_progress : NULL, rows, 1};
    return jc_study_run(def, first, count, &cb, err, err_len);
}

static int on_design_progress(void *ctx, const jc_DesignProgress *p) { return _jcpy_design_progress(ctx, p); }

int jcpy_design_run(jc_DesignDef *def, jc_DesignResult *out, void *pyctx, int with_progress, char *err, size_t err_len)
{
    def->progress = with_progress ? on_design_progress : NULL;
    def->progress_ctx = pyctx;
    return jc_design_run(def, out, err, err_len);
}

static int on_fit_progress(void *ctx, const jc_TrackFitProgress *p) { return _jcpy_fit_progress(ctx, p); }

int jcpy_track_fit(const jc_Setup *setup, const jc_Track *t, jc_TrackFitOptions *o, const jc_SimOptions *sim,
                   jc_TrackFitResult *out, void *pyctx, int with_progress, char *err, size_t err_len)
{
    o->progress = with_progress ? on_fit_progress : NULL;
    o->progress_ctx = pyctx;
    return jc_track_fit(setup, t, o, sim, out, err, err_len);
}
"""


def make_ffi():
    include_dirs, library_dirs = locate()
    inc = _find_header(include_dirs, HEADERS[0])
    decls, macros = _preprocess(inc, [])
    ffi = FFI()
    ffi.cdef(decls)
    ffi.cdef(_constants(macros))
    ffi.cdef(HELPERS_CDEF)
    gsl = _gsl_flags()
    ffi.set_source(
        "jumpcyl._jumpcyl",
        HELPERS_SOURCE,
        include_dirs=[inc] + gsl["include_dirs"],
        library_dirs=library_dirs + gsl["library_dirs"],
        libraries=["jumpcyl"] + gsl["libraries"],
        runtime_library_dirs=library_dirs,
        extra_compile_args=["-std=c17", "-Wall"],
    )
    return ffi


def _gsl_flags():
    out = {"include_dirs": [], "library_dirs": [], "libraries": ["gsl", "gslcblas"]}
    try:
        cflags = subprocess.run(["pkg-config", "--cflags", "gsl"], check=True, capture_output=True,
                                text=True).stdout.split()
        libs = subprocess.run(["pkg-config", "--libs", "gsl"], check=True, capture_output=True,
                              text=True).stdout.split()
    except (OSError, subprocess.CalledProcessError):
        return out
    out["include_dirs"] = [f[2:] for f in cflags if f.startswith("-I")]
    out["library_dirs"] = [f[2:] for f in libs if f.startswith("-L")]
    out["libraries"] = [f[2:] for f in libs if f.startswith("-l") and f != "-lm"]
    return out


ffibuilder = make_ffi()

if __name__ == "__main__":
    ffibuilder.compile(verbose=True)
