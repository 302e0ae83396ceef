// The thesis's room under path transport (scenes/room-path.json) for POV-Ray
// 3.7's radiosity, used by glint-bench --sections indirect to compare POV-Ray's
// indirect light with the hybrid frame's at equal error. POV-Ray is
// left-handed, so z is negated. Declare=Count=N and Declare=ErrorBound=E set
// the radiosity's rays a sample and reuse (defaults 100 and 1.0); render with
// File_Gamma=1.0, as the scene's PNGs are linear.
//
// The materials as glint's path transport reads them (docs/scene-format.md):
// no ambient (radiosity computes that light); a finish whose diffuse
// albedo, specular and reflectivity sum past 1 divided by that sum (the
// floor's light squares 1.12, the mirror 1.68, the gold 1.2); glint's Phong
// lobe normalised, so POV-Ray's phong is specular (h + 2) / 2 (its peak
// under a point light). A point light of colour 1 and attenuation
// 1 / (0.5 + 0.03 d^2) = 2 / (1 + (d / 4.08)^2): fade_distance 4.08,
// fade_power 2. recursion_limit 8: glint's max_bounces.
#version 3.7;
#ifndef (Count) #declare Count = 100; #end
#ifndef (ErrorBound) #declare ErrorBound = 1.0; #end
global_settings {
  assumed_gamma 1.0 max_trace_level 9 adc_bailout 0.001 ambient_light 0
  radiosity {
    count Count error_bound ErrorBound recursion_limit 8 brightness 1
    gray_threshold 0 low_error_factor 0.5 minimum_reuse 0.015 nearest_count 5
    pretrace_start 0.08 pretrace_end 0.01 always_sample off normal off media off adc_bailout 0.001
  }
}
#default { finish { ambient 0 emission 0 } }

camera {
  perspective
  location <0.3, 1.6, -5.2>
  look_at <0, 1.2, 0>
  right x * 4 / 3
  angle 63.75  // horizontal: 2 atan(tan(25 deg) * 4 / 3), for fov_y 50
}

light_source { <1.2, 2.7, -2.0> color rgb 1 fade_distance 4.08 fade_power 2 }

// Floor: checker of 0.75-unit squares, reflective.
union {
  triangle { <-3, 0, -6>, <3, 0, -6>, <3, 0, 3> }
  triangle { <-3, 0, -6>, <3, 0, 3>, <-3, 0, 3> }
  texture {
    checker
      texture {
        pigment { color rgb <0.9, 0.9, 0.85> }
        finish { diffuse 0.8 / 1.12 phong 0.15 / 1.12 * 11 phong_size 20 reflection 0.25 / 1.12 }
      }
      texture {
        pigment { color rgb <0.15, 0.15, 0.2> }
        finish { diffuse 0.8 phong 0.15 * 11 phong_size 20 reflection 0.25 }
      }
    scale 0.75
  }
}
// Back wall, left wall.
union {
  triangle { <-3, 0, 3>, <3, 0, 3>, <3, 3, 3> }
  triangle { <-3, 0, 3>, <3, 3, 3>, <-3, 3, 3> }
  triangle { <-3, 0, -6>, <-3, 0, 3>, <-3, 3, 3> }
  triangle { <-3, 0, -6>, <-3, 3, 3>, <-3, 3, -6> }
  texture { pigment { color rgb <0.85, 0.8, 0.7> } finish { diffuse 0.8 } }
}
// Ceiling.
union {
  triangle { <-3, 3, 3>, <3, 3, 3>, <3, 3, -6> }
  triangle { <-3, 3, 3>, <3, 3, -6>, <-3, 3, -6> }
  texture { pigment { color rgb 0.9 } finish { diffuse 0.8 } }
}
// Mirror on the back wall.
union {
  triangle { <-2.2, 0.5, 2.99>, <0.2, 0.5, 2.99>, <0.2, 2.4, 2.99> }
  triangle { <-2.2, 0.5, 2.99>, <0.2, 2.4, 2.99>, <-2.2, 2.4, 2.99> }
  texture {
    pigment { color rgb 0.8 }
    finish { diffuse 0.1 / 1.68 phong 0.8 / 1.68 * 51 phong_size 100 reflection 0.8 / 1.68 }
  }
}
// Gold sphere.
sphere {
  <0.9, 0.7, 0.6>, 0.7
  texture {
    pigment { color rgb <1.0, 0.78, 0.34> }
    finish { diffuse 0.6 / 1.2 phong 0.3 / 1.2 * 101 phong_size 200 reflection 0.3 / 1.2 }
  }
}
