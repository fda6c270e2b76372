; t005_straight: straight flutes, no blur
teeth    = 5
steps    = even
diameter = 22000
lead     = 0   ; straight flutes
hand     = right
noise    = 0.01
blur     = 0
image    = 640
seed     = 142
