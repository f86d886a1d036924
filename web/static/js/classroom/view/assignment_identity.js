/**
 * The student's personal link, shown once after registering: a button copies it to the clipboard (and selects
 * it, so that it can be copied by hand where no clipboard is offered).
 */
const field = document.getElementById("personal-link");
const button = document.getElementById("copy-link");

button.addEventListener("click", async () => {
  field.select();
  let copied;
  try {
    await navigator.clipboard.writeText(field.value);
    copied = true;
  } catch {                                    // no clipboard API (a page served over plain http)
    copied = document.execCommand("copy");
  }
  if (copied) button.textContent = button.dataset.copied;
});
