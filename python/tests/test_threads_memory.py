"""Threads calling simulate at once, and memory over many calls."""
import os
import threading

import jumpcyl as jc


def test_threads_simulate_concurrently():
    setups = [jc.Setup(incline="%ddeg" % a) for a in (15, 30, 45)] + [jc.Setup(preset=p) for p in jc.presets()]
    serial = [jc.simulate(s, sample_dt=0.01).to_dict() for s in setups]
    results, errors = {}, []

    def work(k):
        try:
            for rep in range(5):
                for i, s in enumerate(setups):
                    d = jc.simulate(s, sample_dt=0.01).to_dict()
                    if d != serial[i]:
                        errors.append((k, rep, i))
            results[k] = True
        except Exception as e:  # pragma: no cover - reported below
            errors.append(e)

    threads = [threading.Thread(target=work, args=(k,)) for k in range(8)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    assert not errors and len(results) == 8


def rss_kb():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") // 1024


CALLS = int(os.environ.get("JUMPCYL_LEAK_CALLS", "100000"))


def test_rss_flat_over_many_calls():
    s = jc.Setup(incline="30deg")
    for _ in range(2000):
        jc.simulate(s).summary
    before = rss_kb()
    for i in range(CALLS):
        r = jc.simulate(s)
        if i % 10 == 0:
            r.events, r.samples
    after = rss_kb()
    # A leak of one event array (8 events x ~150 bytes) per call would be 100 MB.
    assert after - before < 4096, (before, after)
