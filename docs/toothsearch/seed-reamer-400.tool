; The seed's reamer (tests/toothsearch/t004_reamer_seed.tool) framed for the
; README: a 400-pixel camera and less noise, so that the two pictures stay
; near 100 KB.  docs/toothsearch/README-images.sh makes them.
teeth    = 4
steps    = 90, 80, 110, 80   ; degrees between successive teeth, sum 360
diameter = 60000             ; µm
lead     = 250000            ; µm
hand     = right
noise    = 0.003
blur     = 1.5
image    = 400
seed     = 1
