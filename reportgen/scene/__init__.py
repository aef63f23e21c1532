"""What every kind is made of: the scene base (config, presets, stage keys), the
simulate face (:mod:`.simulation`), the report face (:mod:`.report`), the section
content types (:mod:`.content`), the declared results (:mod:`.schema`), the config base
(:mod:`.config`), results in memory (:mod:`.results`) and sweeps (:mod:`.sweep`).  Shared by
every kind; names none."""
