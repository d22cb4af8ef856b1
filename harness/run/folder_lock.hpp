#pragma once
// An exclusive lock on a run folder, held by `dabench run` (rank 0) and `dabench merge` for the
// whole command: taken before anything in the folder is read or written, released on every
// exit. The lock is flock(2) on FOLDER/.dabench.lock, which the kernel drops when the holder
// dies in any way, so a lock file left by a killed process is simply taken over. The file
// names its holder (pid, host, start time) for the refusal of a second process; it is removed
// on release (a process that opened the file just before then sees it unlinked and retries).
// On NFS, flock is carried out as a POSIX lock by the server (Linux ≥ 2.6.12).
#include <string>

namespace dabench {

class FolderLock {
 public:
  // Creates `folder` if absent and locks it; InputError of one line when another process
  // holds it ("<folder>: in use by dabench pid P on HOST since T") or it cannot be locked.
  // `command` names the holder in that message ("run", "merge").
  FolderLock(const std::string& folder, const std::string& command);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  // Unlocks and removes the lock file now (the destructor then does nothing).
  void release();

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace dabench
