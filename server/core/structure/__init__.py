"""Any planar mechanism built from class-II structural (Assur) groups: parse, analyse, compose, plans."""
