"""python_simulate_us for make bench: the median wall time (us) of one
jc.simulate call of the paper's cylinder at 15, 30 and 45 deg, 400 calls
each, as bench/bench.c times the C call (jc_simulate on a model built once:
the Setup keeps its model). Prints the number alone."""
import statistics
import time

import jumpcyl as jc

REPS = 400
times = []
for incline in (15, 30, 45):
    s = jc.Setup(incline="%ddeg" % incline)
    jc.simulate(s)
    for _ in range(REPS):
        t0 = time.perf_counter()
        jc.simulate(s)
        times.append((time.perf_counter() - t0) * 1e6)
print("%.3f" % statistics.median(times))
