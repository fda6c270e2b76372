; t150_saw_fine: 150 teeth, worst noise and blur
teeth    = 150
steps    = even
diameter = 200000
lead     = 2000000
hand     = right
noise    = 0.05
blur     = 2
image    = 1280
seed     = 317
