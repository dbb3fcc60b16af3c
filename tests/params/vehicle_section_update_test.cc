// In-place update of a complete parameter file's vehicle section
// (birotor-identify --update-params): values replaced, everything else kept.
#include "params/vehicle_section_update.h"

#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include "params/birotor_params_yaml.h"
#include "params/estimator_config_yaml.h"
#include "params/vehicle_description_yaml.h"
#include "tests/params/temp_file.h"

namespace birotor {
namespace {

std::string ReadText(const std::string& path) { return testing::ReadTextFile(path); }
std::string WriteTemp(const std::string& text) { return testing::WriteTempFile("vehicle_section_update_", text); }

TEST(VehicleSectionUpdateTest, ShippedEstimatorFileTakesNewValuesAndKeepsTheRest) {
  const std::string original = ReadText("config/estimator.yaml");
  BirotorParams identified;
  identified.tip_mass_kg = 0.30;
  identified.arm_stiffness_n_m_rad = 3100.5;
  identified.gauge_scale[0] = 1.03;
  identified.gauge_offset_rad[1] = -1.0e-5;
  std::string updated, error;
  ASSERT_TRUE(UpdateVehicleSection(original, identified, "2026-12-01T03:00:00Z by test", &updated, &error)) << error;
  const std::string path = WriteTemp(updated);
  // The whole estimator file still loads, with the identified vehicle and the same estimator options.
  const EstimatorConfig before = LoadEstimatorConfig("config/estimator.yaml");
  const EstimatorConfig after = LoadEstimatorConfig(path);
  EXPECT_EQ(BirotorParamsYaml(BirotorModelOf(after.vehicle)), BirotorParamsYaml(identified));
  EXPECT_EQ(after.method, before.method);
  EXPECT_EQ(ReadIdentificationStamp(path), "2026-12-01T03:00:00Z by test");
  // Every comment line of the original is still there; only vehicle lines changed, one stamp line added.
  std::istringstream a(original), b(updated);
  std::string la, lb;
  int original_lines = 0, changed = 0;
  std::vector<std::string> updated_lines;
  while (std::getline(b, lb)) updated_lines.push_back(lb);
  size_t j = 0;
  while (std::getline(a, la)) {
    ++original_lines;
    if (j < updated_lines.size() && updated_lines[j].find("# identified ") != std::string::npos) ++j;
    ASSERT_LT(j, updated_lines.size());
    if (la != updated_lines[j]) {
      ++changed;
      // A changed line keeps its key and its trailing comment.
      EXPECT_EQ(la.substr(0, la.find(':')), updated_lines[j].substr(0, updated_lines[j].find(':')));
      if (la.find('#') != std::string::npos) {
        EXPECT_NE(updated_lines[j].find(la.substr(la.find('#'))), std::string::npos) << updated_lines[j];
      }
    }
    ++j;
  }
  EXPECT_EQ(updated_lines.size(), static_cast<size_t>(original_lines) + 1);
  EXPECT_LE(changed, 16);  // the 14 scalar vehicle keys and the two gauge arrays at most
  // A second update replaces the stamp instead of adding one.
  std::string again;
  ASSERT_TRUE(UpdateVehicleSection(updated, identified, "second", &again, &error)) << error;
  EXPECT_EQ(std::count(again.begin(), again.end(), '\n'), std::count(updated.begin(), updated.end(), '\n'));
  EXPECT_EQ(ReadIdentificationStamp(WriteTemp(again)), "second");
}

TEST(VehicleSectionUpdateTest, IncompleteFileIsRefusedNamingTheKey) {
  std::string updated, error;
  EXPECT_FALSE(UpdateVehicleSection("vehicle:\n  body_mass_kg: 4.0\n", BirotorParams(), "", &updated, &error));
  EXPECT_NE(error.find("tip_mass_kg"), std::string::npos) << error;
  EXPECT_FALSE(UpdateVehicleSection("estimator:\n  method: ekf\n", BirotorParams(), "", &updated, &error));
  EXPECT_NE(error.find("vehicle"), std::string::npos) << error;
}

TEST(VehicleSectionUpdateTest, FileWithoutStampHasNone) {
  EXPECT_EQ(ReadIdentificationStamp("config/reference_vehicle.yaml"), "");
}

// Issue 23 item 7: the --update-params file and its FILE.bak.
class ParameterFileUpdateTest : public ::testing::Test {
 protected:
  void SetUp() override {
    folder_ = ::testing::TempDir() + "/parameter_file_update_XXXXXX";
    ASSERT_NE(mkdtemp(folder_.data()), nullptr);
    path_ = folder_ + "/estimator.yaml";
    std::ofstream(path_) << kOld;
  }
  void TearDown() override { std::filesystem::remove_all(folder_); }
  static mode_t Mode(const std::string& path) {
    struct stat info {};
    EXPECT_EQ(stat(path.c_str(), &info), 0) << path;
    return info.st_mode & 07777;
  }
  static constexpr const char* kOld = "vehicle:\n  tip_mass_kg: 0.25\n";
  static constexpr const char* kNew = "vehicle:\n  tip_mass_kg: 0.3\n";
  std::string folder_;
  std::string path_;
};

TEST_F(ParameterFileUpdateTest, BothFilesKeepModeAndOwner) {
  ASSERT_EQ(chmod(path_.c_str(), 0444), 0);  // was 0444 -> 0644
  const bool root = geteuid() == 0;
  if (root) {
    ASSERT_EQ(chown(path_.c_str(), 0, 1), 0);  // root:daemon became root:root
  }
  ParameterFileUpdate update;
  std::string error;
  ASSERT_TRUE(PrepareParameterFileUpdate(path_, &update, &error)) << error;
  EXPECT_EQ(update.text, kOld);
  EXPECT_EQ(update.backup, update.target + ".bak");
  ASSERT_TRUE(CommitParameterFileUpdate(update, kNew, &error)) << error;
  EXPECT_EQ(ReadText(path_), kNew);
  EXPECT_EQ(ReadText(path_ + ".bak"), kOld);
  for (const std::string& file : {path_, path_ + ".bak"}) {
    EXPECT_EQ(Mode(file), 0444u) << file;
    struct stat info {};
    ASSERT_EQ(stat(file.c_str(), &info), 0);
    if (root) {
      EXPECT_EQ(info.st_gid, 1u) << file;
    }
    EXPECT_TRUE(S_ISREG(info.st_mode));
  }
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(folder_), {}), 2);  // no temporary left
}

// A pre-planted FILE.bak that is a link (to a device or a victim) or a FIFO
// was written through (the FIFO hung): refused before the fit, and again at
// commit if planted during it; nothing is written.
TEST_F(ParameterFileUpdateTest, APlantedBackupThatIsNotARegularFileIsRefusedAndLeftAlone) {
  const std::string victim = folder_ + "/victim";
  std::ofstream(victim) << "precious\n";
  const std::string backup = path_ + ".bak";
  std::string error;
  ParameterFileUpdate update;
  for (const std::string& target : {victim, std::string("/dev/null")}) {
    ASSERT_EQ(symlink(target.c_str(), backup.c_str()), 0);
    EXPECT_FALSE(PrepareParameterFileUpdate(path_, &update, &error));
    EXPECT_NE(error.find("a symbolic link"), std::string::npos) << error;
    ASSERT_EQ(unlink(backup.c_str()), 0);
  }
  ASSERT_EQ(mkfifo(backup.c_str(), 0600), 0);
  EXPECT_FALSE(PrepareParameterFileUpdate(path_, &update, &error));
  EXPECT_NE(error.find("a FIFO"), std::string::npos) << error;
  ASSERT_EQ(unlink(backup.c_str()), 0);
  // Planted between the check and the commit.
  ASSERT_TRUE(PrepareParameterFileUpdate(path_, &update, &error)) << error;
  ASSERT_EQ(symlink(victim.c_str(), backup.c_str()), 0);
  EXPECT_FALSE(CommitParameterFileUpdate(update, kNew, &error));
  EXPECT_EQ(ReadText(victim), "precious\n");
  EXPECT_EQ(ReadText(path_), kOld);
}

// A symbolic link is updated through its target (the link stays a link, the
// backup sits beside the target).
TEST_F(ParameterFileUpdateTest, ASymbolicLinkIsUpdatedThroughItsTarget) {
  const std::string link = folder_ + "/current.yaml";
  ASSERT_EQ(symlink("estimator.yaml", link.c_str()), 0);
  ParameterFileUpdate update;
  std::string error;
  ASSERT_TRUE(PrepareParameterFileUpdate(link, &update, &error)) << error;
  EXPECT_EQ(update.target, std::filesystem::canonical(path_).string());
  ASSERT_TRUE(CommitParameterFileUpdate(update, kNew, &error)) << error;
  struct stat info {};
  ASSERT_EQ(lstat(link.c_str(), &info), 0);
  EXPECT_TRUE(S_ISLNK(info.st_mode));
  EXPECT_EQ(ReadText(link), kNew);
  EXPECT_EQ(ReadText(path_ + ".bak"), kOld);
}

// Not a regular file, or replaced between the check and the commit: refused.
TEST_F(ParameterFileUpdateTest, ASpecialOrChangedFileIsRefused) {
  const std::string fifo = folder_ + "/fifo.yaml";
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  ParameterFileUpdate update;
  std::string error;
  EXPECT_FALSE(PrepareParameterFileUpdate(fifo, &update, &error));
  EXPECT_NE(error.find("a FIFO"), std::string::npos) << error;
  EXPECT_FALSE(PrepareParameterFileUpdate("/dev/zero", &update, &error));
  ASSERT_TRUE(PrepareParameterFileUpdate(path_, &update, &error)) << error;
  std::ofstream(path_) << "vehicle:\n  tip_mass_kg: 0.26\n";  // edited during the fit
  EXPECT_FALSE(CommitParameterFileUpdate(update, kNew, &error));
  EXPECT_NE(error.find("changed since it was checked"), std::string::npos) << error;
  EXPECT_NE(access((path_ + ".bak").c_str(), F_OK), 0);
}

// A description in the N-arm form (config/vehicles/trirotor.yaml): one key of
// every arm set, every other byte kept, the stamp below `vehicle:`.
TEST(VehicleSectionUpdateTest, TheTrirotorsArmsTakeNewValuesAndKeepTheRest) {
  const std::string original = ReadText("config/vehicles/trirotor.yaml");
  std::string updated, error;
  ASSERT_TRUE(
      UpdateDescriptionArmValues(original, "tip_mass_kg", {0.31, 0.32, 0.33}, "2026-12-05 by test", &updated, &error))
      << error;
  const std::string path = WriteTemp(updated);
  const VehicleDescription before = LoadVehicleDescription("config/vehicles/trirotor.yaml");
  VehicleDescription after = LoadVehicleDescription(path);
  EXPECT_EQ(after.arms[0].tip_mass_kg, 0.31);
  EXPECT_EQ(after.arms[1].tip_mass_kg, 0.32);
  EXPECT_EQ(after.arms[2].tip_mass_kg, 0.33);
  for (size_t i = 0; i < 3; ++i) after.arms[i].tip_mass_kg = before.arms[i].tip_mass_kg;
  EXPECT_EQ(FirstDifference(after, before), "");
  EXPECT_EQ(ReadIdentificationStamp(path), "2026-12-05 by test");
  // Line for line: the three tip_mass_kg lines changed (indent kept), one stamp line added.
  std::istringstream a(original), b(updated);
  std::string la, lb;
  std::vector<std::string> changed;
  while (std::getline(b, lb)) {
    if (lb == "  # identified 2026-12-05 by test") continue;
    ASSERT_TRUE(std::getline(a, la));
    if (la != lb) changed.push_back(lb);
  }
  EXPECT_FALSE(std::getline(a, la));
  EXPECT_EQ(changed, (std::vector<std::string>{"      tip_mass_kg: 0.31", "      tip_mass_kg: 0.32",
                                               "      tip_mass_kg: 0.33"}));
  // Again: the stamp is replaced, not added; unchanged values keep their text.
  std::string again;
  ASSERT_TRUE(UpdateDescriptionArmValues(updated, "tip_mass_kg", {0.31, 0.32, 0.33}, "later", &again, &error));
  EXPECT_EQ(again, std::string(updated).replace(updated.find("2026-12-05 by test"), 18, "later"));
}

TEST(VehicleSectionUpdateTest, ArmValuesNeedABlockListOfTheirCount) {
  // Dashes at the column of `arms:`, the key on the dash line, a comment kept,
  // and the same key in another section left alone.
  const std::string text =
      "vehicle:\n  arms:\n  - tip_mass_kg: 1.0   # first\n    length_m: 2\n  - length_m: 2\n    tip_mass_kg: 1\n"
      "  name: x\nother:\n  tip_mass_kg: 5\n";
  std::string updated, error;
  ASSERT_TRUE(UpdateDescriptionArmValues(text, "tip_mass_kg", {2, 3}, "", &updated, &error)) << error;
  EXPECT_EQ(updated,
            "vehicle:\n  arms:\n  - tip_mass_kg: 2     # first\n    length_m: 2\n  - length_m: 2\n    tip_mass_kg: 3\n"
            "  name: x\nother:\n  tip_mass_kg: 5\n");
  EXPECT_FALSE(UpdateDescriptionArmValues(text, "tip_mass_kg", {2, 3, 4}, "", &updated, &error));
  EXPECT_EQ(error, "vehicle.arms: not a block list of 3 arms");
  EXPECT_FALSE(UpdateDescriptionArmValues(text, "damping_n_m_s_rad", {2, 3}, "", &updated, &error));
  EXPECT_EQ(error, "vehicle.arms[0].damping_n_m_s_rad missing");
  // The birotor form has no arms list.
  EXPECT_FALSE(UpdateDescriptionArmValues(ReadText("config/reference_vehicle.yaml"), "tip_mass_kg", {2, 3}, "",
                                          &updated, &error));
  EXPECT_EQ(error, "vehicle.arms: not a block list of 2 arms");
}

}  // namespace
}  // namespace birotor
