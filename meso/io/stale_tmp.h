/* Temporary files of a killed write (common/atomic_file.h names them "<path>.tmp.<pid>"): a run
 * killed while writing a checkpoint, snapshot, summary or log leaves one behind. The next start
 * removes those whose process is gone and says so on stderr. */
#ifndef MESO_IO_STALE_TMP_H
#define MESO_IO_STALE_TMP_H

/* Remove "<prefix>*.tmp.<pid>" in prefix's folder whose <pid> is no running process (this one's
 * and live ones are kept), one stderr line each. Returns how many were removed. */
int stale_tmp_cleanup(const char *prefix);

#endif
