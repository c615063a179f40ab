/* The threads a study or a design search runs on (OpenMP), and the wall
 * clock of a search. */
#include "study_internal.h"

#include <time.h>

#ifdef _OPENMP
#include <omp.h>
#endif

int jc_thread_count(int threads)
{
    if (threads > 0) return threads;
#ifdef _OPENMP
    return omp_get_max_threads();
#else
    return 1;
#endif
}

int jc_thread_index(void)
{
#ifdef _OPENMP
    return omp_get_thread_num();
#else
    return 0;
#endif
}

double jc_wall_s(void)
{
    struct timespec ts;
    if (timespec_get(&ts, TIME_UTC) != TIME_UTC) return 0.0;
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}
