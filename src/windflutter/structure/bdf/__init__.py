"""NASTRAN bulk data: card tables (:mod:`.cards`), beam-section mapping (:mod:`.beam`), the
deck writer (:mod:`.write`) and reader (:mod:`.read`).  The public entry points are
:func:`windflutter.structure.io_bdf.write_bdf` and :func:`~windflutter.structure.io_bdf.read_bdf`."""
