# OpenCV core + imgproc only (Debian's libopencv-imgproc-dev ships no CMake config,
# and the full libopencv-dev pulls in hundreds of packages we do not use).
find_path(OPENCV_INCLUDE_DIR opencv2/imgproc.hpp PATH_SUFFIXES opencv4 REQUIRED)
find_library(OPENCV_CORE_LIB NAMES opencv_core REQUIRED)
find_library(OPENCV_IMGPROC_LIB NAMES opencv_imgproc REQUIRED)
add_library(cbr_opencv INTERFACE)
target_include_directories(cbr_opencv SYSTEM INTERFACE ${OPENCV_INCLUDE_DIR})
target_link_libraries(cbr_opencv INTERFACE ${OPENCV_IMGPROC_LIB} ${OPENCV_CORE_LIB})
