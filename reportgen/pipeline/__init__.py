"""The staged pipeline: configs -> simulate -> figures -> report -> index, each stage run
only when its inputs changed (:mod:`.stages`), sweeps (:mod:`.sweep`), the edit loop
(:mod:`.watch`), worker processes (:mod:`.forked`), stage keys (:mod:`.codestamp`), the
peer-measurement cache (:mod:`.cache`) and the output folder's files (:mod:`.layout`,
:mod:`.fsutil`).  Names no kind."""
