; t020_straight
teeth    = 20
steps    = even
diameter = 70000
lead     = 0   ; straight flutes
hand     = right
noise    = 0.02
blur     = 1
image    = 768
seed     = 226
