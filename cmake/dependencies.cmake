# Every find_package of the project, once. Modules link the imported targets they need.
find_package(Eigen3 REQUIRED NO_MODULE)
find_package(Boost REQUIRED COMPONENTS program_options)
find_package(OpenMP REQUIRED COMPONENTS CXX)
find_package(nlohmann_json REQUIRED)

# PCL's config pulls in VTK and friends; ask only for the components we link.
find_package(PCL 1.12 REQUIRED COMPONENTS common)
# PCL_COMMON_LIBRARIES is a plain list; wrap it in one interface target with SYSTEM includes.
add_library(pc_pcl_common INTERFACE)
target_include_directories(pc_pcl_common SYSTEM INTERFACE ${PCL_INCLUDE_DIRS})
target_link_libraries(pc_pcl_common INTERFACE pcl_common Eigen3::Eigen)
target_compile_definitions(pc_pcl_common INTERFACE ${PCL_DEFINITIONS})

if(PC_BUILD_TESTS)
    find_package(GTest REQUIRED)
    # Tests compare our reader with PCL's own PCD reader/writer. PCL's `io` component would make
    # CMake load VTK's config, which on Debian bookworm fails without MPI; the PCD code needs no
    # VTK header, so link the library directly.
    find_library(PC_PCL_IO_LIBRARY NAMES pcl_io REQUIRED)
    add_library(pc_pcl_io INTERFACE)
    target_link_libraries(pc_pcl_io INTERFACE ${PC_PCL_IO_LIBRARY} pc_pcl_common)
endif()

# Images (masks, renders). calib3d only for the tests' projection oracle (cv::projectPoints).
find_package(OpenCV REQUIRED COMPONENTS core imgproc imgcodecs calib3d)
