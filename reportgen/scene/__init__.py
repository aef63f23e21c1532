"""What every kind is made of: the scene base (config, presets, stage keys), the
simulate face (:mod:`.simulation`), the report face (:mod:`.report`), the section
content types (:mod:`.content`) and the declared results (:mod:`.schema`).  Shared by
every kind; names none."""
