"""The command line (:mod:`.cli`) and the commands that are more than a stage: the
stability audit (:mod:`.audit`) and the benchmarks (:mod:`.bench`, :mod:`.bench_nbody`,
:mod:`.bench_pipeline`)."""
