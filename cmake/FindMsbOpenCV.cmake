# Finds the OpenCV 4 modules msbench uses from Debian's per-module -dev packages and defines
# imported targets opencv::<module>. Debian ships OpenCVConfig.cmake only in the libopencv-dev
# meta package, which would pull in highgui/Qt; highgui must never be linked (it breaks the
# OSMesa GL lookup), so it is deliberately not offered here.
find_path(MsbOpenCV_INCLUDE_DIR opencv2/core.hpp PATH_SUFFIXES opencv4)
set(_msb_cv_modules core imgproc video features2d calib3d flann)
set(MsbOpenCV_FOUND TRUE)
foreach(m IN LISTS _msb_cv_modules)
  find_library(MsbOpenCV_${m}_LIBRARY opencv_${m})
  if(NOT MsbOpenCV_${m}_LIBRARY OR NOT MsbOpenCV_INCLUDE_DIR)
    set(MsbOpenCV_FOUND FALSE)
    message(STATUS "OpenCV module ${m} not found (install libopencv-${m}-dev)")
    continue()
  endif()
  if(NOT TARGET opencv::${m})
    add_library(opencv::${m} UNKNOWN IMPORTED)
    set_target_properties(opencv::${m} PROPERTIES
      IMPORTED_LOCATION ${MsbOpenCV_${m}_LIBRARY}
      INTERFACE_INCLUDE_DIRECTORIES ${MsbOpenCV_INCLUDE_DIR})
  endif()
endforeach()
# imgcodecs (reading images) only for the measurement tool texture-stats: optional.
find_library(MsbOpenCV_imgcodecs_LIBRARY opencv_imgcodecs)
if(MsbOpenCV_imgcodecs_LIBRARY AND MsbOpenCV_INCLUDE_DIR AND EXISTS ${MsbOpenCV_INCLUDE_DIR}/opencv2/imgcodecs.hpp
   AND NOT TARGET opencv::imgcodecs)
  add_library(opencv::imgcodecs UNKNOWN IMPORTED)
  set_target_properties(opencv::imgcodecs PROPERTIES
    IMPORTED_LOCATION ${MsbOpenCV_imgcodecs_LIBRARY}
    INTERFACE_INCLUDE_DIRECTORIES ${MsbOpenCV_INCLUDE_DIR})
endif()
include(FindPackageHandleStandardArgs)
find_package_handle_standard_args(MsbOpenCV REQUIRED_VARS MsbOpenCV_INCLUDE_DIR MsbOpenCV_FOUND)
