;;; eglot-test.el --- the Emacs setup of docs/editors.md, run headless  -*- lexical-binding: t -*-
;; Evaluates the elisp block under "### Emacs (eglot)" of docs/editors.md as a user's init file would,
;; opens a program with a broken modifier and checks what the user gets through eglot: the mode, the
;; server's diagnostic on its line (Flymake), the hover of Y=IC(10), and the diagnostic gone after an
;; edit that repairs the line. Prints `N passed, N failed` and exits 1 on a failure.

(require 'cl-lib)
(require 'package)
;; `emacs -Q` leaves out the system's ELPA packages, where Debian's elpa-eglot lives.
(add-to-list 'package-directory-list "/usr/share/emacs/site-lisp/elpa")
(package-initialize)

(defvar sinumerik-test-repository
  (expand-file-name "../../../" (file-name-directory (or load-file-name buffer-file-name))))
(defvar sinumerik-test-passed 0)
(defvar sinumerik-test-failed 0)

(defun sinumerik-test-check (name fn)
  "Runs FN, which returns (OK . DETAIL), and reports NAME."
  (let ((result (condition-case error (funcall fn) (error (cons nil (format "%S" error))))))
    (if (car result)
        (progn (cl-incf sinumerik-test-passed) (princ (format "ok     %s\n" name)))
      (cl-incf sinumerik-test-failed)
      (princ (format "FAILED %s: %s\n" name (cdr result))))))

(defun sinumerik-test-wait (predicate seconds)
  "Waits up to SECONDS for PREDICATE, serving the server's messages and timers meanwhile."
  (let ((deadline (+ (float-time) seconds)) value)
    (while (and (not (setq value (funcall predicate))) (< (float-time) deadline))
      (accept-process-output nil 0.05)
      (run-hooks 'post-command-hook))
    value))

(defun sinumerik-test-snippet ()
  "The elisp block under the Emacs heading of docs/editors.md."
  (with-temp-buffer
    (insert-file-contents (expand-file-name "docs/editors.md" sinumerik-test-repository))
    (search-forward "### Emacs (eglot)")
    (search-forward "```elisp\n")
    (buffer-substring-no-properties (point) (progn (search-forward "\n```") (match-beginning 0)))))

(defun sinumerik-test-diagnostics ()
  "The Flymake diagnostics of the buffer as (LINE . TEXT), LINE 1-based."
  (mapcar (lambda (d) (cons (line-number-at-pos (flymake-diagnostic-beg d)) (flymake-diagnostic-text d)))
          (flymake-diagnostics)))

(let* ((binary (or (getenv "SINUMERIK_LSP_BIN")
                   (expand-file-name "target/release/sinumerik-lsp" sinumerik-test-repository)))
       (folder (make-temp-file "sinumerik-emacs" t))
       (program (expand-file-name "PART.MPF" folder)))
  ;; The snippet starts `sinumerik-lsp` from PATH, as a user's setup would.
  (setq exec-path (cons (file-name-directory binary) exec-path))
  (setenv "PATH" (concat (file-name-directory binary) path-separator (getenv "PATH")))
  (with-temp-file program
    (insert "N10 G17 G90 G54 T1 D1 M6\nN20 G0 X0 Y0 Z5\nN30 G1 Z-2 F300\nN40 X40 Y=IC(10)\nN50 X=AC 5\nN60 M30\n"))
  (condition-case error
      (progn
        (eval (car (read-from-string (concat "(progn " (sinumerik-test-snippet) ")"))) t)
        (require 'eglot)
        (find-file program)
        (sinumerik-test-check "the snippet gives .MPF files sinumerik-mode"
          (lambda () (cons (eq major-mode 'sinumerik-mode) major-mode)))
        ;; eglot-ensure connects after the next command, which post-command-hook stands for here.
        (run-hooks 'post-command-hook)
        (sinumerik-test-check "eglot starts sinumerik-lsp for the buffer"
          (lambda () (cons (sinumerik-test-wait (lambda () (and (eglot-current-server) eglot--managed-mode)) 20)
                           "no server")))
        (sinumerik-test-check "Flymake shows the server's S101 on line 5 (X=AC 5)"
          (lambda ()
            (let ((found (sinumerik-test-wait
                          (lambda () (flymake-start)
                            (cl-find-if (lambda (d) (and (= (car d) 5) (string-match-p "parentheses" (cdr d))))
                                        (sinumerik-test-diagnostics)))
                          20)))
              (cons found (format "%S" (sinumerik-test-diagnostics))))))
        (sinumerik-test-check "the hover of Y=IC(10) says Y = 0.000 + 10.000 = 10.000 mm"
          (lambda ()
            (goto-char (point-min))
            (search-forward "Y=IC")
            (goto-char (match-beginning 0))
            (let* ((answer (jsonrpc-request (eglot-current-server) :textDocument/hover
                                            (eglot--TextDocumentPositionParams)))
                   (contents (plist-get answer :contents))
                   (text (if (stringp contents) contents (plist-get contents :value))))
              (cons (and text (string-match-p "Y = 0\\.000 \\+ 10\\.000 = \\*\\*10\\.000\\*\\* mm\\|Y = 0\\.000 \\+ 10\\.000 = 10\\.000 mm" text))
                    (format "%S" answer)))))
        (sinumerik-test-check "an edit that adds the parentheses clears the diagnostic"
          (lambda ()
            (goto-char (point-min))
            (search-forward "X=AC 5")
            (replace-match "X=AC(5)" t t)
            ;; eglot sends the change from an idle timer, and a batch Emacs is never idle.
            (eglot--signal-textDocument/didChange)
            (let ((cleared (sinumerik-test-wait
                            (lambda () (flymake-start)
                              (not (cl-find-if (lambda (d) (string-match-p "parentheses" (cdr d)))
                                               (sinumerik-test-diagnostics))))
                            20)))
              (cons cleared (format "%S" (sinumerik-test-diagnostics))))))
        (set-buffer-modified-p nil)
        (ignore-errors (eglot-shutdown (eglot-current-server))))
    (error (cl-incf sinumerik-test-failed)
           (princ (format "FAILED the test ran to its end: %S\n" error))))
  (delete-directory folder t)
  (princ (format "%d passed, %d failed\n" sinumerik-test-passed sinumerik-test-failed))
  (kill-emacs (if (> sinumerik-test-failed 0) 1 0)))
