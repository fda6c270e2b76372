; t002_straight_uneven: two straight flutes, uneven
teeth    = 2
steps    = 172.615, 187.385
diameter = 8000
lead     = 0   ; straight flutes
hand     = right
noise    = 0.03
blur     = 2
image    = 512
seed     = 107
