# SPDX-License-Identifier: BSD-3-Clause
"""shell_word: any text, control characters and quotes included, becomes one line that bash
reads back as the same single word."""

from __future__ import annotations

import random
import subprocess
import unittest

from gencoord.cxx.escapes import shell_word

ALPHABET = "ab /'\"\\$`!*?~\n\t\r\x01\x7f é"


class ShellWordTest(unittest.TestCase):
    def test_bash_reads_back_every_text_from_one_line(self):
        rng = random.Random(7)
        texts = ["", "plain", "out dir", "a\nb", "ends\\", "it's", "\x7f"]
        texts += ["".join(rng.choice(ALPHABET) for _ in range(rng.randint(1, 12)))
                  for _ in range(200)]
        words = [shell_word(text) for text in texts]
        for word in words:
            self.assertNotIn("\n", word)
            self.assertFalse(word.endswith("\\"), word)
        output = subprocess.run(["bash", "-c", "printf '%s\\0' " + " ".join(words)],
                                check=True, capture_output=True).stdout  # bytes: \r kept
        read = output.decode("utf-8").split("\0")[:-1]
        self.assertEqual(read, texts)

    def test_ordinary_words_are_left_as_they_are(self):
        self.assertEqual(shell_word("models/n_link_chain.py"), "models/n_link_chain.py")
        self.assertEqual(shell_word("n=5"), "n=5")


if __name__ == "__main__":
    unittest.main()
