// The thesis's room (scenes/room.json) for POV-Ray 3.7, used by glint-bench
// to time POV-Ray on the same scene. POV-Ray is left-handed, so z is negated.
// Attenuation 1 / (0.5 + 0.03 d^2) = 2 / (1 + (d / 4.08)^2): fade_distance
// 4.08, fade_power 2. Render: +W640 +H480 +A0.0 +AM1 +R2 +J1.0 (4 jittered
// samples per pixel).
#version 3.7;
global_settings { assumed_gamma 1.0 max_trace_level 5 adc_bailout 0.01 ambient_light 1 }

camera {
  perspective
  location <0.3, 1.6, -5.2>
  look_at <0, 1.2, 0>
  right x * 4 / 3
  angle 63.75  // horizontal: 2 atan(tan(25 deg) * 4 / 3), for fov_y 50
}

light_source { <1.2, 2.7, -2.0> color rgb 1 fade_distance 4.08 fade_power 2 }

#declare Wall = texture { pigment { color rgb <0.85, 0.8, 0.7> } finish { ambient 0.1 diffuse 0.8 } }

// Floor: checker of 0.75-unit squares, reflective.
union {
  triangle { <-3, 0, -6>, <3, 0, -6>, <3, 0, 3> }
  triangle { <-3, 0, -6>, <3, 0, 3>, <-3, 0, 3> }
  texture {
    pigment { checker color rgb <0.9, 0.9, 0.85> color rgb <0.15, 0.15, 0.2> scale 0.75 }
    finish { ambient 0.1 diffuse 0.8 phong 0.15 phong_size 20 reflection 0.25 }
  }
}
// Back wall, left wall.
union {
  triangle { <-3, 0, 3>, <3, 0, 3>, <3, 3, 3> }
  triangle { <-3, 0, 3>, <3, 3, 3>, <-3, 3, 3> }
  triangle { <-3, 0, -6>, <-3, 0, 3>, <-3, 3, 3> }
  triangle { <-3, 0, -6>, <-3, 3, 3>, <-3, 3, -6> }
  texture { Wall }
}
// Ceiling.
union {
  triangle { <-3, 3, 3>, <3, 3, 3>, <3, 3, -6> }
  triangle { <-3, 3, 3>, <3, 3, -6>, <-3, 3, -6> }
  texture { pigment { color rgb 0.9 } finish { ambient 0.1 diffuse 0.8 } }
}
// Mirror on the back wall.
union {
  triangle { <-2.2, 0.5, 2.99>, <0.2, 0.5, 2.99>, <0.2, 2.4, 2.99> }
  triangle { <-2.2, 0.5, 2.99>, <0.2, 2.4, 2.99>, <-2.2, 2.4, 2.99> }
  texture {
    pigment { color rgb 0.8 }
    finish { ambient 0.02 diffuse 0.1 phong 0.8 phong_size 100 reflection 0.8 }
  }
}
// Gold sphere.
sphere {
  <0.9, 0.7, 0.6>, 0.7
  texture {
    pigment { color rgb <1.0, 0.78, 0.34> }
    finish { ambient 0.1 diffuse 0.6 phong 0.3 phong_size 200 reflection 0.3 }
  }
}
