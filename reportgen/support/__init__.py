"""The plumbing every layer uses: atomic writes, locks and links (:mod:`.fsutil`), where
files are and which are safe to read back (:mod:`.layout`), forked worker processes that
die with their parent (:mod:`.forked`), the user cache of peer measurements
(:mod:`.cache`), hashes of the code a stage imports (:mod:`.codestamp`), timing
(:mod:`.timing`).  Names no kind; imports nothing of reportgen above it."""
