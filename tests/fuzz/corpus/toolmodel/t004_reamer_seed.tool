; the seed manual's reamer: 4 teeth at 90, 80, 110, 80 degrees, helical
teeth    = 4
steps    = 90, 80, 110, 80   ; degrees between successive teeth, sum 360
diameter = 60000             ; µm
lead     = 250000            ; µm
hand     = right
noise    = 0.02
blur     = 1.5
image    = 768
seed     = 1
