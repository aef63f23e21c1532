"""The staged pipeline: configs -> simulate -> figures -> report -> index, each stage run
only when its inputs changed (:mod:`.stages`), and the edit loop (:mod:`.watch`).  Names
no kind."""
