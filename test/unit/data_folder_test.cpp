#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>

#include "virtual_origami/core/data_folder.h"

using namespace virtual_origami::core;
namespace fs = std::filesystem;

namespace
{
/// A fresh folder under the system's temporary folder, removed with the fixture.
class DataFolderTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    base_ = fs::temp_directory_path() / ("vo_data_folder_test_" + std::to_string(std::random_device{}()));
    fs::create_directories(base_ / "outside");
    std::ofstream(base_ / "outside" / "secret.fold") << "{}";
    const Expected<DataFolder> opened = DataFolder::open((base_ / "data").string());
    ASSERT_TRUE(opened) << opened.message();
    folder_ = std::make_unique<DataFolder>(*opened);
  }
  void TearDown() override
  {
    fs::remove_all(base_);
  }

  fs::path base_;
  std::unique_ptr<DataFolder> folder_;
};
}  // namespace

TEST_F(DataFolderTest, RelativePathsResolveInTheDataFolder)
{
  EXPECT_TRUE(fs::is_directory(base_ / "data"));  // made by open
  const Expected<std::string> path = folder_->resolve("models/crane.fold");
  ASSERT_TRUE(path) << path.message();
  EXPECT_EQ(*path, (fs::canonical(base_ / "data") / "models" / "crane.fold").string());
  const Expected<std::string> absolute = folder_->resolve((base_ / "data" / "a.fold").string());
  ASSERT_TRUE(absolute) << absolute.message();
  EXPECT_EQ(*absolute, (fs::canonical(base_ / "data") / "a.fold").string());
}

TEST_F(DataFolderTest, PathsOutsideAreRefused)
{
  for (const std::string& path :
       { std::string("/etc/passwd"), std::string("/etc/x.fold"), (base_ / "outside" / "secret.fold").string(),
         std::string("../outside/secret.fold"), std::string("models/../../outside/secret.fold"),
         std::string("a/../b.fold"), std::string("") })
  {
    const Expected<std::string> resolved = folder_->resolve(path);
    EXPECT_FALSE(resolved) << path << " resolved to " << (resolved ? *resolved : "");
    if (!resolved)
    {
      EXPECT_FALSE(resolved.message().empty());
    }
  }
}

TEST_F(DataFolderTest, SymlinksLeavingTheFolderAreRefused)
{
  fs::create_symlink(base_ / "outside" / "secret.fold", base_ / "data" / "link.fold");
  fs::create_directory_symlink(base_ / "outside", base_ / "data" / "linked_folder");
  fs::create_symlink(base_ / "outside" / "new.fold", base_ / "data" / "dangling.fold");
  EXPECT_FALSE(folder_->resolve("link.fold"));
  EXPECT_FALSE(folder_->resolve("linked_folder/secret.fold"));
  EXPECT_FALSE(folder_->resolve("linked_folder/new.fold"));
  EXPECT_FALSE(folder_->resolve("dangling.fold"));  // save would create the file outside
  // A link that stays inside is fine.
  std::ofstream(base_ / "data" / "real.fold") << "{}";
  fs::create_symlink(base_ / "data" / "real.fold", base_ / "data" / "inner.fold");
  EXPECT_TRUE(folder_->resolve("inner.fold"));
}

TEST_F(DataFolderTest, ALaunchCanAllowMoreFolders)
{
  const Expected<DataFolder> wider = DataFolder::open((base_ / "data").string(), { (base_ / "outside").string() });
  ASSERT_TRUE(wider) << wider.message();
  EXPECT_TRUE(wider->resolve((base_ / "outside" / "secret.fold").string()));
  EXPECT_FALSE(wider->resolve("/etc/passwd"));
  EXPECT_FALSE(DataFolder::open((base_ / "data").string(), { (base_ / "missing").string() }));
  EXPECT_FALSE(DataFolder::open(""));
}
