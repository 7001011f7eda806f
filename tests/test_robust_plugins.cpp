// Plugins that are not what they claim, and the scratch folder their copies live in (issue 13):
//   validateDescriptor on the raw descriptor (counts, ids, ranges, enum labels), before anything
//   is copied; the broken test plugins (bad_*.so) refused by the scan with the file named; two
//   libraries claiming one id refused naming both; create() returning null reported by name;
//   /tmp/shadowlab-<pid> removed when done and stale folders of dead processes cleaned.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/time.h>
#include <unistd.h>

#include <cmath>
#include <cstddef>
#include <fstream>
#include <limits>

#include "plugin/plugin_library.h"
#include "test_support.h"
#include "util/scratch_dir.h"

using namespace shadowlab;
namespace fs = std::filesystem;

namespace {

#define EXPECT_MENTIONS(message, part) EXPECT_NE((message).find(part), std::string::npos) << (message)

const fs::path kTestPlugins = fs::path(SHADOWLAB_BUILD_DIR) / "test_plugins";

// A valid descriptor to break one field at a time.
struct SampleDescriptor {
    ParamDesc params[4] = {
        {"resolution", "resolution", ParamType::Int, 256, 8192, 2048, "texels", "", nullptr},
        {"bias", "bias", ParamType::Float, 0, 4, 0.5, "", "", nullptr},
        {"filter", "filter", ParamType::Bool, 0, 1, 0, "", "", nullptr},
        {"format", "format", ParamType::Enum, 0, 2, 2, "", "", "16|24|32F"},
    };
    TechniqueDesc desc{.structSize = sizeof(TechniqueDesc),
                       .id = "sample",
                       .displayName = "Sample",
                       .category = "hard",
                       .explanation = "An explanation.",
                       .shadowGlsl = "sample.glsl",
                       .params = params,
                       .paramCount = 4};
};

void setOld(const fs::path& dir) {
    const struct timeval times[2] = {{::time(nullptr) - 3600, 0}, {::time(nullptr) - 3600, 0}};
    ::utimes(dir.c_str(), times);
}

} // namespace

TEST(RobustDescriptor, ValidatesTheRawDescriptorBeforeCopyingIt) {
    SampleDescriptor s;
    EXPECT_EQ(validateDescriptor(s.desc), "");

    auto problem = [](auto&& change) {
        SampleDescriptor broken;
        change(broken);
        return validateDescriptor(broken.desc);
    };
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.structSize = 8; }), "structSize 8 is too small");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.paramCount = 100000000; }), "paramCount 100000000 is more than 256");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.params = nullptr; }), "params is null");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.id = nullptr; }), "id is null");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.id = ""; }), "id is empty");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.id = "pcf.v2"; }), "has a character other than");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.shadowGlsl = nullptr; }), "shadowGlsl is null");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[1].id = nullptr; }), "parameter 1: id is null");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[1].id = "a=b"; }), "parameter 1: id");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[2].id = "resolution"; }), "'resolution' is declared twice");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[1].defaultValue = 9; }), "'bias': default outside its range");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[1].maxValue = std::numeric_limits<double>::infinity(); }),
                    "'bias': min, max and default must be finite");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[1].minValue = std::nan(""); }), "must be finite");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[0].defaultValue = 2048.5; }), "needs whole min, max and default");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[2].maxValue = 2; }), "a bool parameter has the range 0 to 1");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[3].enumLabels = "16|24"; }),
                    "'format': enum labels do not match its range (2 labels need min 0 and max 1)");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[3].enumLabels = nullptr; }), "enumLabels is null");
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.params[0].type = static_cast<ParamType>(7); }), "unknown type 7");
    static const std::string longId(65, 'a');
    EXPECT_MENTIONS(problem([](SampleDescriptor& b) { b.desc.id = longId.c_str(); }), "longer than 64 bytes");
}

// The translucency model, added after flags: read only when structSize covers it.
TEST(RobustDescriptor, TranslucencyModelIsReadOnlyWhereTheDescriptorHasIt) {
    SampleDescriptor s;
    EXPECT_EQ(copyDescriptor(s.desc, {}).translucencyModel, TranslucencyModel::Opaque) << "the default";
    s.desc.translucencyModel = TranslucencyModel::Coverage;
    EXPECT_EQ(validateDescriptor(s.desc), "");
    EXPECT_EQ(copyDescriptor(s.desc, {}).translucencyModel, TranslucencyModel::Coverage);
    // An older plugin's descriptor ends at flags: whatever lies beyond is not its, and not read.
    s.desc.structSize = offsetof(TechniqueDesc, flags) + sizeof(uint32_t);
    EXPECT_EQ(validateDescriptor(s.desc), "");
    EXPECT_EQ(copyDescriptor(s.desc, {}).translucencyModel, TranslucencyModel::Opaque);
    SampleDescriptor bad;
    bad.desc.translucencyModel = static_cast<TranslucencyModel>(9);
    EXPECT_MENTIONS(validateDescriptor(bad.desc), "translucencyModel 9 is not one of 0-4");
    bad.desc.structSize = offsetof(TechniqueDesc, translucencyModel);
    EXPECT_EQ(validateDescriptor(bad.desc), "") << "not covered by structSize: not read";
}

// Flag conditions (added after translucencyModel): a flag that holds only for some values of a
// parameter; checked against the descriptor's own flags and parameters, read only when covered.
TEST(RobustDescriptor, FlagConditionsNarrowTheFlagsByParameterValue) {
    const FlagCondition onlyFor32F[] = {{kTechniqueNeedsCameraPrepass, "format", "24|32F"}};
    SampleDescriptor s;
    s.desc.flags = kTechniqueNeedsCameraPrepass;
    s.desc.flagConditions = onlyFor32F;
    s.desc.flagConditionCount = 1;
    EXPECT_EQ(validateDescriptor(s.desc), "");
    const TechniqueInfo info = copyDescriptor(s.desc, {});
    ASSERT_EQ(info.flagRules.size(), 1u);
    // Values in descriptor order: format (index 3) 0 = "16", 1 = "24", 2 = "32F".
    EXPECT_EQ(info.flagsFor({2048, 0.5, 0, 2}), uint32_t(kTechniqueNeedsCameraPrepass));
    EXPECT_EQ(info.flagsFor({2048, 0.5, 0, 1}), uint32_t(kTechniqueNeedsCameraPrepass));
    EXPECT_EQ(info.flagsFor({2048, 0.5, 0, 0}), 0u);
    // Numbers for numeric parameters; a flag no condition names holds always.
    const FlagCondition onBias[] = {{kTechniqueNeedsCameraPrepass, "bias", "0.5|1"}};
    s.desc.flagConditions = onBias;
    const TechniqueInfo byBias = copyDescriptor(s.desc, {});
    EXPECT_EQ(byBias.flagsFor({2048, 1.0, 0, 0}), uint32_t(kTechniqueNeedsCameraPrepass));
    EXPECT_EQ(byBias.flagsFor({2048, 2.0, 0, 0}), 0u);
    s.desc.flagConditionCount = 0;
    EXPECT_EQ(copyDescriptor(s.desc, {}).flagsFor({2048, 2.0, 0, 0}), uint32_t(kTechniqueNeedsCameraPrepass));

    auto problem = [](const FlagCondition& condition, uint32_t flags = kTechniqueNeedsCameraPrepass) {
        SampleDescriptor broken;
        broken.desc.flags = flags;
        broken.desc.flagConditions = &condition;
        broken.desc.flagConditionCount = 1;
        return validateDescriptor(broken.desc);
    };
    EXPECT_MENTIONS(problem({kTechniqueNeedsCameraPrepass, "fit", "sdsm"}), "flagConditions[0]: 'fit' is not one of");
    EXPECT_MENTIONS(problem({kTechniqueNeedsCameraPrepass, "format", "16|48"}), "flagConditions[0]: parameter 'format'");
    EXPECT_MENTIONS(problem({kTechniqueNeedsCameraPrepass, "bias", "9"}), "flagConditions[0]: parameter 'bias'");
    EXPECT_MENTIONS(problem({kTechniqueNeedsCameraPrepass, "format", ""}), "values is empty");
    EXPECT_MENTIONS(problem({kTechniqueNeedsCameraPrepass, nullptr, "16"}), "param is null");
    EXPECT_MENTIONS(problem({kTechniqueNeedsCameraPrepass, "format", "16"}, 0), "not a non-empty subset");
    SampleDescriptor nullConditions;
    nullConditions.desc.flagConditionCount = 2;
    EXPECT_MENTIONS(validateDescriptor(nullConditions.desc), "flagConditions is null");
    // An older descriptor (ending at translucencyModel) has none, whatever follows it.
    nullConditions.desc.structSize = offsetof(TechniqueDesc, flagConditions);
    EXPECT_EQ(validateDescriptor(nullConditions.desc), "");
    EXPECT_TRUE(copyDescriptor(nullConditions.desc, {}).flagRules.empty());
}

TEST(RobustDescriptor, TheScanRefusesEveryBrokenPluginByNameAndKeepsTheGoodOne) {
    const fs::path dir = fs::temp_directory_path() / ("shadowlab-robust-scan-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(kTestPlugins / "reload_v1.so", dir / "reload_v1.so");
    const std::pair<const char*, const char*> broken[] = {
        {"bad_huge_param_count.so", "paramCount 100000000 is more than 256"},
        {"bad_null_param_id.so", "parameter 0: id is null"},
        {"bad_nan_default.so", "must be finite"},
        {"bad_enum_mismatch.so", "enum labels do not match"},
        {"bad_unknown_type.so", "unknown type 7"},
        {"bad_duplicate_param.so", "declared twice"},
        {"bad_dotted_id.so", "'bad.dotted' has a character"},
    };
    for (const auto& [file, problem] : broken) fs::copy_file(kTestPlugins / file, dir / file);
    const PluginScan scan = scanPlugins(dir);
    ASSERT_EQ(scan.techniques.size(), 1u);
    EXPECT_EQ(scan.techniques[0].id, "reload_test");
    ASSERT_EQ(scan.errors.size(), std::size(broken));
    for (const auto& [file, problem] : broken) {
        bool found = false;
        for (const std::string& error : scan.errors)
            found |= error.find((dir / file).string()) != std::string::npos && error.find(problem) != std::string::npos;
        EXPECT_TRUE(found) << file << ": no error naming it with '" << problem << "'";
    }
    fs::remove_all(dir);
}

TEST(RobustDescriptor, TwoLibrariesClaimingOneIdAreBothRefusedNamingBoth) {
    const fs::path dir = fs::temp_directory_path() / ("shadowlab-robust-dup-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    for (const char* file : {"bad_duplicate_a.so", "bad_duplicate_b.so", "reload_v1.so"}) fs::copy_file(kTestPlugins / file, dir / file);
    const PluginScan scan = scanPlugins(dir);
    ASSERT_EQ(scan.techniques.size(), 1u);
    EXPECT_EQ(scan.techniques[0].id, "reload_test");
    ASSERT_EQ(scan.errors.size(), 1u);
    EXPECT_MENTIONS(scan.errors[0], "technique id 'duplicate_test' is claimed by 2 libraries");
    EXPECT_MENTIONS(scan.errors[0], (dir / "bad_duplicate_a.so").string());
    EXPECT_MENTIONS(scan.errors[0], (dir / "bad_duplicate_b.so").string());
    fs::remove_all(dir);
}

TEST(RobustDescriptor, CreateReturningNullIsAnErrorNamingTheLibrary) {
    const fs::path dir = fs::temp_directory_path() / ("shadowlab-robust-create-" + std::to_string(::getpid()));
    fs::remove_all(dir);
    fs::create_directories(dir);
    fs::copy_file(kTestPlugins / "bad_create_null.so", dir / "bad_create_null.so");
    fs::copy_file(kTestPlugins / "reload_v1.so", dir / "reload_v1.so");
    setenv("SHADOWLAB_PLUGIN_DIR", dir.c_str(), 1);
    {
        auto app = test::makeHeadlessApp("cube", {64, 48});
        ASSERT_TRUE(app);
        std::string error;
        EXPECT_FALSE(app->renderFrame("create_null", error));
        EXPECT_MENTIONS(error, "bad_create_null.so");
        EXPECT_MENTIONS(error, "create() returned nothing");
    }
    unsetenv("SHADOWLAB_PLUGIN_DIR");
    fs::remove_all(dir);
}

TEST(RobustScratch, StaleFoldersOfDeadProcessesGoTheLiveOnesStay) {
    const fs::path tmp = fs::temp_directory_path() / ("shadowlab-robust-tmp-" + std::to_string(::getpid()));
    fs::remove_all(tmp);
    fs::create_directories(tmp);
    auto folder = [&](const std::string& name, bool withLock) {
        fs::create_directories(tmp / name);
        std::ofstream(tmp / name / "copy.so") << "x";
        if (withLock) std::ofstream(tmp / name / ".lock");
        setOld(tmp / name);
        return tmp / name;
    };
    // pid_max is at most 2^22 on Linux: 999999999 is no process.
    const fs::path dead = folder("shadowlab-999999999", false);
    const fs::path deadWithLock = folder("shadowlab-999999998-1", true);
    const fs::path unlockedOfALivePid = folder("shadowlab-" + std::to_string(::getpid()) + "-7", true);
    const fs::path held = folder("shadowlab-" + std::to_string(::getppid()) + "-9", true);
    const int fd = ::open((held / ".lock").c_str(), O_RDONLY);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    const fs::path young = tmp / "shadowlab-999999997";
    fs::create_directories(young);   // might be between mkdir and flock: left alone
    const fs::path other = folder("shadowlab-dragon-1.json", false);
    const fs::path noLockLivePid = folder("shadowlab-" + std::to_string(::getppid()), false);

    EXPECT_EQ(removeStaleScratchDirs(tmp), 3);
    EXPECT_FALSE(fs::exists(dead));
    EXPECT_FALSE(fs::exists(deadWithLock));
    EXPECT_FALSE(fs::exists(unlockedOfALivePid)) << "a lock nobody holds is stale whatever the pid";
    EXPECT_TRUE(fs::exists(held)) << "its lock is held";
    EXPECT_TRUE(fs::exists(young));
    EXPECT_TRUE(fs::exists(other)) << "not a scratch folder name";
    EXPECT_TRUE(fs::exists(noLockLivePid)) << "an old-style folder of a live process";
    ::close(fd);
    fs::remove_all(tmp);
}

TEST(RobustScratch, TheFolderIsRemovedWhenDoneAndRecreatedOnUse) {
    std::string error;
    const fs::path dir = scratchDir(error);
    ASSERT_FALSE(dir.empty()) << error;
    EXPECT_EQ(dir.filename().string().rfind("shadowlab-" + std::to_string(::getpid()), 0), 0u);
    EXPECT_TRUE(fs::exists(dir / ".lock"));
    {
        std::string openError;
        auto library = PluginLibrary::open(kTestPlugins / "reload_v1.so", openError);
        ASSERT_TRUE(library) << openError;
        size_t copies = 0;
        for (const auto& item : fs::directory_iterator(dir)) copies += item.path().extension() == ".so";
        EXPECT_EQ(copies, 1u);
    }
    size_t copies = 0;
    for (const auto& item : fs::directory_iterator(dir)) copies += item.path().extension() == ".so";
    EXPECT_EQ(copies, 0u) << "a closed library's copy is removed";
    removeScratchDir();
    EXPECT_FALSE(fs::exists(dir));
    EXPECT_EQ(scratchDir(error), dir) << "created again on next use";
    removeScratchDir();
}
