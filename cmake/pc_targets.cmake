# The three helpers every CMakeLists.txt below the top uses.

# -Wno-missing-field-initializers: designated initialisers ({.eps = 0.1}) are the house pattern.
set(PC_WARNING_FLAGS -Wall -Wextra -Wpedantic -Wshadow -Wno-missing-field-initializers)
if(PC_WARNINGS_AS_ERRORS)
    list(APPEND PC_WARNING_FLAGS -Werror)
endif()

# pc_add_module(NAME SOURCES <src...> DEPS <targets...>): static library pc_<NAME>, alias pc::<NAME>.
function(pc_add_module name)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_library(pc_${name} STATIC ${ARG_SOURCES})
    add_library(pc::${name} ALIAS pc_${name})
    target_include_directories(pc_${name} PUBLIC
        $<BUILD_INTERFACE:${CMAKE_CURRENT_SOURCE_DIR}/include>
        $<INSTALL_INTERFACE:include>)
    target_compile_options(pc_${name} PRIVATE ${PC_WARNING_FLAGS})
    target_link_libraries(pc_${name} PUBLIC ${ARG_DEPS})
endfunction()

# pc_add_tool(NAME DEPS <targets...>): tools/<NAME>.cpp -> build/bin/<NAME>.
function(pc_add_tool name)
    cmake_parse_arguments(ARG "" "" "DEPS" ${ARGN})
    add_executable(${name} ${name}.cpp)
    target_compile_options(${name} PRIVATE ${PC_WARNING_FLAGS})
    target_link_libraries(${name} PRIVATE pc::cli ${ARG_DEPS})
    install(TARGETS ${name} RUNTIME DESTINATION bin)
    set_property(GLOBAL APPEND PROPERTY PC_TOOLS ${name})
endfunction()

# pc_add_test(MODULE SOURCES <src...> DEPS <targets...>): one gtest executable test_<MODULE>.
function(pc_add_test module)
    cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
    add_executable(test_${module} ${ARG_SOURCES})
    set_target_properties(test_${module} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${PROJECT_BINARY_DIR}/tests)
    target_compile_options(test_${module} PRIVATE ${PC_WARNING_FLAGS})
    target_include_directories(test_${module} PRIVATE ${PROJECT_SOURCE_DIR}/tests)
    target_compile_definitions(test_${module} PRIVATE
        PC_SAMPLE_CLOUDS_DIR="${PROJECT_SOURCE_DIR}/sample_clouds"
        PC_TOOLS_DIR="${CMAKE_RUNTIME_OUTPUT_DIRECTORY}"
        PC_DOCS_DIR="${PROJECT_SOURCE_DIR}/docs"
        $<$<BOOL:${PC_SANITIZE}>:PC_SANITIZE>)
    target_link_libraries(test_${module} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gtest_main)
    # A test past its timeout fails (a hang); under the sanitizers code runs about five times
    # slower (the slowest chain test: 10-13 s in Release, 57-79 s under ASan), so the margin
    # scales with it.
    if(PC_SANITIZE)
        set(timeout 400)
    else()
        set(timeout 120)
    endif()
    gtest_discover_tests(test_${module} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT ${timeout})
endfunction()
