// The sweep runner (stickslip/sweep/sweep.hpp): the thread backend gives the serial backend's
// rows, a throwing item loses only its own row, progress sees every item once, and the CSV.
#include <stickslip/sweep.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <unistd.h>

namespace sweep_test {

using namespace stickslip;

// Item k: the partial sum of the Leibniz series to k + 1 terms (a row that depends on k alone),
// with a cost growing with k (so threads finish out of order); items k % 5 == 3 throw.
std::string leibniz_item(std::size_t k) {
  if (k % 5 == 3) throw std::invalid_argument("item " + std::to_string(k) + ": bad parameter");
  double s = 0;
  for (std::size_t i = 0; i <= k; ++i) s += (i % 2 ? -4.0 : 4.0) / double(2 * i + 1);
  std::this_thread::sleep_for(std::chrono::microseconds(200 * (k % 7)));
  std::ostringstream o;
  o.precision(17);
  o << k << ',' << s;
  return o.str();
}

TEST(Sweep, ThreadsGiveTheSerialRowsAndAThrowingItemLosesOnlyItself) {
  constexpr std::size_t n = 23;
  const auto serial = run_sweep_serial(n, leibniz_item);
  for (unsigned threads : {1u, 2u, 3u, 8u}) {
    std::vector<int> seen(n, 0);
    std::size_t last_done = 0;
    const auto threaded = run_sweep_threads(n, leibniz_item, threads,
                                            [&](std::size_t done, std::size_t count, std::size_t k, const SweepOutcome&) {
                                              EXPECT_EQ(count, n);
                                              EXPECT_EQ(done, last_done + 1);  // one call at a time, in order of completion
                                              last_done = done;
                                              ++seen[k];
                                            });
    ASSERT_EQ(threaded.size(), n);
    for (std::size_t k = 0; k < n; ++k) {
      EXPECT_EQ(seen[k], 1) << "item " << k << " with " << threads << " threads";
      EXPECT_EQ(threaded[k].ok, serial[k].ok);
      EXPECT_EQ(threaded[k].row, serial[k].row);
      EXPECT_EQ(threaded[k].error, serial[k].error);
    }
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (k % 5 == 3) {
      EXPECT_FALSE(serial[k].ok);
      EXPECT_EQ(serial[k].error, "item " + std::to_string(k) + ": bad parameter");
      continue;
    }
    ASSERT_TRUE(serial[k].ok) << serial[k].error;
    // The row is item k's own: the series converges to pi with error below 4 / (2k + 3)
    // (alternating series bound), an independent check that row k was computed for k.
    const double s = std::stod(serial[k].row.substr(serial[k].row.find(',') + 1));
    EXPECT_LE(std::abs(s - M_PI), 4.0 / double(2 * k + 3));
    EXPECT_EQ(std::stoul(serial[k].row), k);
  }
}

TEST(Sweep, CsvKeepsTheKeyOfAFailedItemAndQuotesItsError) {
  std::vector<SweepOutcome> outcomes(3);
  outcomes[0] = {true, "1,a", ""};
  outcomes[1] = {false, "", "bad \"x\", really"};
  outcomes[2] = {true, "3,c", ""};
  std::ostringstream os;
  write_sweep_csv(os, "key", [](std::size_t k) { return "k" + std::to_string(k); }, "n,s", outcomes);
  EXPECT_EQ(os.str(), "key,n,s,error\nk0,1,a,\nk1,,,\"bad \"\"x\"\", really\"\nk2,3,c,\n");
}

TEST(Sweep, EmptyItemOrKeyIsRejected) {
  EXPECT_THROW(run_sweep_serial(3, SweepItem{}), std::invalid_argument);
  EXPECT_THROW(run_sweep_threads(3, SweepItem{}), std::invalid_argument);
  std::ostringstream os;
  EXPECT_THROW(write_sweep_csv(os, "k", SweepKey{}, "a", {}), std::invalid_argument);
  // No items: nothing runs, an empty result.
  EXPECT_TRUE(run_sweep_threads(0, leibniz_item, 4).empty());
}

// The journal: a sweep that ends early (here: after items 0 and 3, the last line cut while it was
// written) is resumed with the rest of its items, and the outcomes then equal an uninterrupted
// run's; rows and errors with line breaks and backslashes survive; another sweep's journal, an
// item index out of range and a garbled line are refused naming the file.
TEST(SweepJournal, ResumingKeepsWhatFinishedAndRunsTheRest) {
  constexpr std::size_t n = 9;
  const auto item = [](std::size_t k) {
    if (k == 4) throw std::invalid_argument("item 4:\nbad \\ value");
    return k == 3 ? std::string("3,multi\nline \\n") : leibniz_item(k);
  };
  const auto reference = run_sweep_serial(n, item);
  const std::string path =
      (std::filesystem::temp_directory_path() / ("sweep_journal_test_" + std::to_string(::getpid()))).string();
  {
    SweepJournal journal(path, "settings A", false);
    journal.record(0, reference[0]);
    journal.record(3, reference[3]);
    journal.record(4, reference[4]);
  }
  {  // killed while writing item 4's line: its line is cut short
    std::ifstream in(path, std::ios::binary);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    in.close();
    std::ofstream(path, std::ios::binary | std::ios::trunc) << text.substr(0, text.size() - 5);
  }
  auto done = read_sweep_journal(path, "settings A", n);
  ASSERT_EQ(done.size(), n);
  std::vector<std::size_t> pending;
  for (std::size_t k = 0; k < n; ++k)
    if (!done[k]) pending.push_back(k);
  EXPECT_EQ(pending, (std::vector<std::size_t>{1, 2, 4, 5, 6, 7, 8}));
  {
    SweepJournal journal(path, "settings A", true);
    for (std::size_t k : pending) journal.record(k, run_sweep_item(item, k));
  }
  done = read_sweep_journal(path, "settings A", n);
  for (std::size_t k = 0; k < n; ++k) {
    ASSERT_TRUE(done[k].has_value()) << k;
    EXPECT_EQ(done[k]->ok, reference[k].ok) << k;
    EXPECT_EQ(done[k]->row, reference[k].row) << k;
    EXPECT_EQ(done[k]->error, reference[k].error) << k;
  }
  EXPECT_EQ(reference[4].error, "item 4:\nbad \\ value");
  // Not this sweep's journal, or not one of its items.
  EXPECT_THROW(read_sweep_journal(path, "settings B", n), std::invalid_argument);
  EXPECT_THROW(read_sweep_journal(path, "settings A", 5), std::invalid_argument);
  std::ofstream(path, std::ios::app) << "x ok 1\n";
  EXPECT_THROW(read_sweep_journal(path, "settings A", n), std::invalid_argument);
  // A new journal (not resumed) starts empty; a missing file is an empty journal.
  { SweepJournal fresh(path, "settings A", false); }
  done = read_sweep_journal(path, "settings A", n);
  EXPECT_TRUE(std::none_of(done.begin(), done.end(), [](const auto& d) { return d.has_value(); }));
  std::filesystem::remove(path);
  EXPECT_EQ(read_sweep_journal(path, "settings A", n).size(), n);
}

}  // namespace sweep_test
